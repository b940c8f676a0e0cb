#pragma once
/// \file
/// The inputs and signals a link (remote, serial) serves: chosen by glob patterns at configure,
/// resolved to handles and readers, read and written in update() without a lookup.

#include <s2sim/sdk.hpp>

#include <sstream>
#include <string>
#include <vector>

namespace s2sim::links {

struct ServedSet {
  std::vector<NamedUnit> inputs;
  std::vector<NamedUnit> signals;
  std::vector<InputHandle> input_handles;
  std::vector<SignalReader> readers;

  /// Reads the `inputs` and `signals` attributes (space-separated globs, in order, duplicates
  /// once); by default everything of the owning robot (`robots/<robot>/*`), or of the scene
  /// (`*`) for a scene-level link. Must run before the link declares its own signals, so that
  /// they are not served. A glob written in the scene that matches nothing is a located error.
  void configure(ConfigureContext& ctx) {
    const Params& p = ctx.params();
    const std::string fallback =
        ctx.robot().empty() ? std::string("*") : "robots/" + std::string(ctx.robot()) + "/*";
    inputs =
        select(p, "inputs", fallback, [&](const std::string& g) { return ctx.input_names(g); });
    signals =
        select(p, "signals", fallback, [&](const std::string& g) { return ctx.signal_names(g); });
    for (const auto& in : inputs)
      input_handles.push_back(ctx.input(in.name));
    for (const auto& s : signals)
      readers.push_back(ctx.signal_reader(s.name));
  }

 private:
  template <class Lookup>
  static std::vector<NamedUnit> select(const Params& p, const char* attribute,
                                       const std::string& fallback, Lookup lookup) {
    std::istringstream globs(p.text(attribute, fallback));
    std::vector<NamedUnit> out;
    for (std::string g; globs >> g;) {
      const std::vector<NamedUnit> found = lookup(g);
      if (found.empty() && p.has(attribute))  // the default may find nothing (no inputs)
        throw Error(ErrorKind::scene, p.where(attribute),
                    std::string("'") + g + "' matches no " +
                        (std::string(attribute) == "inputs" ? "input" : "signal") +
                        " (s2sim-run SCENE --list-inputs / --list-signals lists them)");
      for (const auto& f : found) {
        bool seen = false;
        for (const auto& o : out)
          seen = seen || o.name == f.name;
        if (!seen) out.push_back(f);
      }
    }
    return out;
  }
};

}  // namespace s2sim::links
