/// \file
/// `<defines>` blocks (simtwo-format.md §2.1): `<const>` defines or overwrites, `<arg>` defines
/// only when the enclosing scope has not; anything else (`<noconst>`) is a disabled entry.

#include "scene/loading.hpp"

namespace s2sim::scene::detail {

void apply_defines(const Element& defines, const Reader& r, ConstantTable& table) {
  for (const Element& c : defines.children) {
    if (c.name != "const" && c.name != "arg") continue;
    const std::string name = r.text(c, "name", "");
    if (name.empty()) r.fail(c, "name", "missing constant name");
    // A failing value is an error here (SimTwo silently reuses the previous value).
    const double value = r.required_number(c, "value");
    table.declare(name, c.name == "arg");
    if (c.name == "const") {
      table.set(name, value);
    } else {
      table.define_if_absent(name, value);
    }
  }
}

}  // namespace s2sim::scene::detail
