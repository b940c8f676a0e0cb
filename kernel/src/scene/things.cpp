/// \file
/// Things files (simtwo-format.md §6): free bodies outside any robot, same vocabulary as
/// robot solids; their `<defines>` go into a copy of G.

#include "scene/loading.hpp"
#include "scene/xml.hpp"

#include <vector>

namespace s2sim::scene::detail {
namespace {

/// The children of a `<things>` element: its `<defines>` into `scope`, its solids as things.
void load_things_element(LoadContext& ctx, const Reader& r, const Element& things,
                         ConstantTable& scope) {
  for (const Element& el : things.children) {
    if (el.name == "defines") {
      apply_defines(el, r, scope);
    } else if (is_solid_element(el.name)) {
      if (auto body = load_solid(ctx, r, el, -1, ctx.scene.things))
        ctx.scene.things.push_back(*body);
    }
  }
}

}  // namespace

void load_things_file(LoadContext& ctx, const std::filesystem::path& file,
                      const ConstantTable& globals) {
  const std::string display = ctx.display(file);
  const std::vector<Element> top = read_xml_file_elements(file, display);
  ConstantTable scope = globals;
  const Reader r(display, scope);
  if (top.size() == 1 && top.front().name == "things") {
    load_things_element(ctx, r, top.front(), scope);
    return;
  }
  // `<defines>` beside `<things>`: at the top of the file, or under a root of another name.
  // SimTwo reads only a root `<things>` (SelectSingleNode('/things')), so its constants stay
  // undefined there; here they apply, in document order, to this file's things.
  const std::vector<Element>& list = top.size() == 1 ? top.front().children : top;
  bool found = false;
  for (const Element& el : list)
    found = found || el.name == "things";
  if (!found)
    throw Error(ErrorKind::scene, Location{display, top.front().path, ""},
                "expected a <things> file, found <" + top.front().name + ">");
  for (const Element& el : list) {
    if (el.name == "defines") {
      apply_defines(el, r, scope);
      ctx.warn(r.at(el),
               "<defines> beside <things> applied to this file's things (SimTwo reads only a "
               "root <things>, where these constants are undefined)");
    } else if (el.name == "things") {
      load_things_element(ctx, r, el, scope);
    } else {
      ctx.warn(r.at(el), "<" + el.name + "> beside <things> ignored");
    }
  }
}

}  // namespace s2sim::scene::detail
