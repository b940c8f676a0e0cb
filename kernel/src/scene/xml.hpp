#pragma once
/// \file
/// Reads SimTwo XML files into `scene::Element` trees, tolerant the way SimTwo (OmniXML) is:
/// a BOM and anything before the first `<` are skipped, and comments such as `<!-------->`
/// load. Syntax errors throw `s2sim::Error` naming the file and the line.

#include <s2sim/kernel/scene.hpp>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace s2sim::scene {

/// Parses `text` as the content of a file shown as `display_name` in messages; returns the
/// root element. Element paths start at the root's name (`robot/solids/cuboid[2]`).
Element parse_xml(std::string text, const std::string& display_name);

/// Reads and parses the file at `path`; `display_name` is what messages call it (the path
/// relative to the scene folder).
Element read_xml_file(const std::filesystem::path& path, const std::string& display_name);

/// Every top-level element of `text`, in document order: OmniXML, like RapidXML, accepts a
/// file with several (a things file with `<defines>` beside `<things>`). Paths are their
/// names, with `[n]` where a name repeats.
std::vector<Element> parse_xml_elements(std::string text, const std::string& display_name);

/// `parse_xml_elements` of the file at `path`.
std::vector<Element> read_xml_file_elements(const std::filesystem::path& path,
                                            const std::string& display_name);

}  // namespace s2sim::scene
