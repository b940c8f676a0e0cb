/// \file
/// XML reading through Boost.PropertyTree (attributes under `<xmlattr>`, comments under
/// `<xmlcomment>`), converted into `Element` trees that keep document order and paths.

#include "scene/xml.hpp"

#include "scene/limits.hpp"

#include <boost/property_tree/detail/rapidxml.hpp>
#include <boost/property_tree/ptree.hpp>
#include <boost/property_tree/xml_parser.hpp>

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace s2sim::scene {
namespace {

namespace pt = boost::property_tree;

std::string trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(first, last - first + 1));
}

// ptree keys starting with '<' are its own bookkeeping (<xmlattr>, <xmlcomment>, <xmltext>).
bool is_element_key(const std::string& key) {
  return !key.empty() && key[0] != '<';
}

Element convert(const std::string& name, const pt::ptree& tree, const std::string& path) {
  Element el;
  el.name = name;
  el.path = path;
  std::map<std::string, int> count;
  for (const auto& [key, child] : tree)
    if (is_element_key(key)) ++count[key];
  std::map<std::string, int> seen;
  for (const auto& [key, child] : tree) {
    if (key == "<xmlattr>") {
      for (const auto& [attr, value] : child)
        el.attributes.emplace_back(attr, trim(value.data()));
    } else if (is_element_key(key)) {
      std::string child_path = path + "/" + key;
      // The index is written only where it disambiguates, so paths of unique children stay
      // short: robot/solids/cuboid[2] but robot/solids.
      if (count[key] > 1) child_path.append("[").append(std::to_string(++seen[key])).append("]");
      el.children.push_back(convert(key, child, child_path));
    }
  }
  return el;
}

/// Boost.PropertyTree does not check that closing tags match (`<robot>...</robt>` loads), so
/// the text is first parsed by the RapidXML it bundles with closing-tag validation on.
void check_well_formed(const std::string& text, const std::string& display_name) {
  namespace rx = pt::detail::rapidxml;
  std::vector<char> buffer(text.begin(), text.end());
  buffer.push_back('\0');
  rx::xml_document<char> doc;
  try {
    doc.parse<rx::parse_validate_closing_tags | rx::parse_non_destructive>(buffer.data());
  } catch (const rx::parse_error& e) {
    const char* where = e.where<char>();
    const char* begin = buffer.data();
    const auto line = 1 + std::count(begin, where ? where : begin, '\n');
    throw Error(ErrorKind::scene, Location{display_name + ":" + std::to_string(line), "", ""},
                e.what());
  }
}

/// Refuses elements nested deeper than limits::kMaxXmlDepth before any recursive parser sees
/// them (40 000 levels overflowed the stack), and files of more than limits::kMaxXmlElements
/// elements before any tree is built (a million things needed 36 times the file's size in
/// memory): a linear scan of the tags, skipping comments, CDATA, processing instructions and
/// declarations, quotes respected inside tags.
void check_nesting_depth(const std::string& text, const std::string& display_name) {
  std::int64_t depth = 0, elements = 0;
  auto skip_to = [&](std::size_t from, const char* end) {
    const auto at = text.find(end, from);
    return at == std::string::npos ? text.size() : at + std::char_traits<char>::length(end);
  };
  for (std::size_t i = text.find('<'); i < text.size(); i = text.find('<', i)) {
    if (text.compare(i, 4, "<!--") == 0) {
      i = skip_to(i + 4, "-->");
    } else if (text.compare(i, 9, "<![CDATA[") == 0) {
      i = skip_to(i + 9, "]]>");
    } else if (text.compare(i, 2, "<?") == 0) {
      i = skip_to(i + 2, "?>");
    } else if (text.compare(i, 2, "<!") == 0) {
      i = skip_to(i + 2, ">");
    } else if (text.compare(i, 2, "</") == 0) {
      --depth;
      i = skip_to(i + 2, ">");
    } else {
      char quote = 0;
      std::size_t j = i + 1;
      for (; j < text.size(); ++j) {
        const char c = text[j];
        if (quote) {
          if (c == quote) quote = 0;
        } else if (c == '"' || c == '\'') {
          quote = c;
        } else if (c == '>') {
          break;
        }
      }
      if (++elements > limits::kMaxXmlElements) {
        const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(i), '\n');
        throw Error(
            ErrorKind::scene, Location{display_name + ":" + std::to_string(line), "", ""},
            "more than " + std::to_string(limits::kMaxXmlElements) + " elements in one file");
      }
      if (j < text.size() && text[j - 1] != '/' && ++depth > limits::kMaxXmlDepth) {
        const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(i), '\n');
        throw Error(
            ErrorKind::scene, Location{display_name + ":" + std::to_string(line), "", ""},
            "elements nested deeper than " + std::to_string(limits::kMaxXmlDepth) + " levels");
      }
      i = j;
    }
  }
}

pt::ptree parse_tree(std::string text, const std::string& display_name) {
  if (text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.erase(0, 3);
  // SimTwo accepts text before the declaration (MotorModel_V3AGM/Motor.xml starts with a
  // space and a blank line). Drop it but keep its line breaks so error lines stay right.
  const auto first_tag = text.find('<');
  if (first_tag == std::string::npos)
    throw Error(ErrorKind::scene, Location{display_name, "", ""}, "no XML element in the file");
  const auto breaks = std::count(text.begin(), text.begin() + first_tag, '\n');
  text = std::string(static_cast<std::size_t>(breaks), '\n') + text.substr(first_tag);

  check_nesting_depth(text, display_name);
  check_well_formed(text, display_name);
  std::istringstream in(text);
  pt::ptree tree;
  try {
    pt::read_xml(in, tree);
  } catch (const pt::xml_parser_error& e) {
    // "file:line" in the file part gives the compiler-style "scene.xml:12: expected >".
    throw Error(ErrorKind::scene, Location{display_name + ":" + std::to_string(e.line()), "", ""},
                e.message());
  }
  return tree;
}

std::string read_text(const std::filesystem::path& path, const std::string& display_name) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(ErrorKind::scene, Location{display_name, "", ""}, "cannot open the file");
  std::ostringstream content;
  content << in.rdbuf();
  return content.str();
}

}  // namespace

Element parse_xml(std::string text, const std::string& display_name) {
  const pt::ptree tree = parse_tree(std::move(text), display_name);
  for (const auto& [key, child] : tree)
    if (is_element_key(key)) return convert(key, child, key);
  throw Error(ErrorKind::scene, Location{display_name, "", ""}, "no XML element in the file");
}

std::vector<Element> parse_xml_elements(std::string text, const std::string& display_name) {
  const pt::ptree tree = parse_tree(std::move(text), display_name);
  std::map<std::string, int> count, seen;
  for (const auto& [key, child] : tree)
    if (is_element_key(key)) ++count[key];
  std::vector<Element> out;
  for (const auto& [key, child] : tree) {
    if (!is_element_key(key)) continue;
    std::string path = key;
    if (count[key] > 1) path.append("[").append(std::to_string(++seen[key])).append("]");
    out.push_back(convert(key, child, path));
  }
  return out;
}

Element read_xml_file(const std::filesystem::path& path, const std::string& display_name) {
  return parse_xml(read_text(path, display_name), display_name);
}

std::vector<Element> read_xml_file_elements(const std::filesystem::path& path,
                                            const std::string& display_name) {
  return parse_xml_elements(read_text(path, display_name), display_name);
}

}  // namespace s2sim::scene
