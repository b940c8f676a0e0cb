/// \file
/// Drive-train children shared by `<articulations>` and `<wheels>` (simtwo-format.md §4.10),
/// kept as written for the drive-train plugin: the loader only resolves SimTwo's inheritance
/// (`<default>`, a Universal joint's `*2` children), attribute by attribute.

#include "scene/loading.hpp"

#include <array>
#include <memory>

namespace s2sim::scene::detail {
namespace {

constexpr std::array<std::string_view, 7> kDriveElements = {
    "motor", "gear", "rotor", "encoder", "controller", "friction", "spring"};

/// The drive-train element `child` names with `suffix` (`motor2` with "2"), or empty.
std::string_view drive_base(const Element& child, std::string_view suffix) {
  for (std::string_view base : kDriveElements)
    if (child.name.size() == base.size() + suffix.size() &&
        child.name.compare(0, base.size(), base) == 0 &&
        child.name.compare(base.size(), std::string::npos, suffix) == 0)
      return base;
  return {};
}

}  // namespace

ParamSource drive_train_source(const Reader& reader, std::shared_ptr<const ConstantTable> constants,
                               const Element& at) {
  ParamSource p;
  p.element.name = "drive_train";
  p.element.path = reader.at(at).element;
  p.file = reader.file();
  p.constants = std::move(constants);
  return p;
}

bool read_drive_child(const Element& c, std::string_view suffix, ParamSource& drive) {
  const std::string_view base = drive_base(c, suffix);
  if (base.empty()) return false;
  auto& children = drive.element.children;
  Element* own = nullptr;
  for (Element& e : children)
    if (e.name == base) own = &e;
  if (!own) {
    Element e = c;
    e.name = std::string(base);  // `motor2` is the second axis's `motor`
    children.push_back(std::move(e));
    return true;
  }
  // Overlay: the attributes written here replace or join the inherited ones, which keep the
  // path they were written at (errors name it).
  if (own->attribute_paths.size() != own->attributes.size())
    own->attribute_paths.assign(own->attributes.size(), own->path);
  if (base == "controller" && !c.attribute("mode")) {
    // SimTwo re-reads the mode at every <controller>: an absent one resets it (quirk 7b).
    for (std::size_t i = 0; i < own->attributes.size(); ++i)
      if (own->attributes[i].first == "mode") {
        own->attributes.erase(own->attributes.begin() + static_cast<std::ptrdiff_t>(i));
        own->attribute_paths.erase(own->attribute_paths.begin() + static_cast<std::ptrdiff_t>(i));
        break;
      }
  }
  for (const auto& [name, value] : c.attributes) {
    bool replaced = false;
    for (std::size_t i = 0; i < own->attributes.size() && !replaced; ++i)
      if (own->attributes[i].first == name) {
        own->attributes[i].second = value;
        own->attribute_paths[i] = c.path;
        replaced = true;
      }
    if (!replaced) {
      own->attributes.emplace_back(name, value);
      own->attribute_paths.push_back(c.path);
    }
  }
  own->path = c.path;  // absent attributes are reported where the axis's own element is
  return true;
}

}  // namespace s2sim::scene::detail
