/// \file
/// S2Sim's `<plugin kind='…' id='…'>` extension at the top level of scene.xml or a robot
/// file: the element is handed to the kind's factory through its ParamSource.

#include "scene/loading.hpp"

#include <memory>

namespace s2sim::scene::detail {

void load_plugin(LoadContext& ctx, const Reader& r, const Element& el, int robot) {
  Scene& scene = ctx.scene;
  PluginInstance p;
  p.kind = r.text(el, "kind", "");
  if (p.kind.empty()) r.fail(el, "kind", "missing plugin kind");
  const int n = ++ctx.plugin_count[p.kind];
  p.id = r.text(el, "id", "");
  if (p.id.empty()) p.id = p.kind + std::to_string(n);
  p.robot = robot;
  p.where = r.at(el);
  p.params = ParamSource{el, r.file(), std::make_shared<ConstantTable>(r.constants())};
  scene.plugins.push_back(std::move(p));
  if (robot >= 0)
    scene.robots[static_cast<std::size_t>(robot)].plugins.push_back(
        static_cast<int>(scene.plugins.size() - 1));
}

}  // namespace s2sim::scene::detail
