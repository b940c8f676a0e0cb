// s2sim-view: the viewer. World view, run control, configuration, chart, sheet, scene editor
// and log over the same Simulation façade as s2sim-run (docs/viewer.md).
#include "app.hpp"
#include "exit_codes.hpp"
#include "options.hpp"

#include <s2sim/error.hpp>
#include <s2sim/kernel/simulation.hpp>

#include <cstdio>
#include <new>
#include <system_error>

int main(int argc, char** argv) {
  try {
    const auto options = s2sim::viewer::parse_options(argc, argv);
    if (options.help) {
      std::fputs(s2sim::viewer::usage_text(), stdout);
      return 0;
    }
    return s2sim::viewer::run_viewer(options);
  } catch (const s2sim::Error& e) {
    std::fprintf(stderr, "s2sim-view: error: %s\n", e.what());
    return s2sim::exit_code(e.kind());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "s2sim-view: error: %s\n", s2sim::apps::kOutOfMemoryText);
    return s2sim::apps::kExitCannotGoOn;
  } catch (const std::system_error& e) {
    std::fprintf(stderr, "s2sim-view: error: %s: %s\n", s2sim::apps::kResourceRefusedText,
                 e.what());
    return s2sim::apps::kExitCannotGoOn;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "s2sim-view: internal error: %s\n", e.what());
    return s2sim::apps::kExitCannotGoOn;
  }
}
