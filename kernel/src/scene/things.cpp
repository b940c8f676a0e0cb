/// \file
/// Things files (simtwo-format.md §6): free bodies outside any robot, same vocabulary as
/// robot solids; their `<defines>` go into a copy of G.

#include "scene/loading.hpp"
#include "scene/xml.hpp"

namespace s2sim::scene::detail {

void load_things_file(LoadContext& ctx, const std::filesystem::path& file,
                      const ConstantTable& globals) {
  const std::string display = ctx.display(file);
  const Element root = read_xml_file(file, display);
  if (root.name != "things")
    throw Error(ErrorKind::scene, Location{display, root.path, ""},
                "expected a <things> file, found <" + root.name + ">");
  ConstantTable scope = globals;
  const Reader r(display, scope);
  for (const Element& el : root.children) {
    if (el.name == "defines") {
      apply_defines(el, r, scope);
    } else if (is_solid_element(el.name)) {
      if (auto body = load_solid(ctx, r, el, -1, ctx.scene.things))
        ctx.scene.things.push_back(*body);
    }
  }
}

}  // namespace s2sim::scene::detail
