#include "peer_model.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace peers {

std::array<double, 2> grid_position(int index, int count) {
  constexpr double kSpacing_m = 1.5;
  const int cols = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))));
  return {(index % cols) * kSpacing_m, (index / cols) * kSpacing_m};
}

namespace {

[[noreturn]] void fail(const std::filesystem::path& file, int line, const std::string& what) {
  throw std::runtime_error(file.string() + ":" + std::to_string(line) + ": " + what);
}

std::ifstream open(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot be read");
  return in;
}

/// The numbers of attribute `name="a b c"` in `line`.
std::vector<double> attribute(const std::string& line, const std::string& name,
                              const std::filesystem::path& file, int line_no) {
  const std::string key = " " + name + "=\"";
  const auto at = line.find(key);
  if (at == std::string::npos) fail(file, line_no, "no attribute " + name);
  const auto start = at + key.size();
  std::istringstream in(line.substr(start, line.find('"', start) - start));
  std::vector<double> values;
  for (double v; in >> v;)
    values.push_back(v);
  return values;
}

}  // namespace

ArticulatedModel read_articulated(const std::filesystem::path& table) {
  std::ifstream in = open(table);
  ArticulatedModel model;
  int line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string kind;
    fields >> kind;
    if (kind == "body") {
      BoxBody b;
      fields >> b.name >> b.mass_kg;
      for (double& v : b.size_m)
        fields >> v;
      for (double& v : b.centre_m)
        fields >> v;
      if (!fields || b.mass_kg <= 0) fail(table, line_no, "malformed body");
      model.bodies.push_back(b);
    } else if (kind == "hinge") {
      HingeSpec h;
      fields >> h.name >> h.child >> h.parent;
      for (double& v : h.axis)
        fields >> v;
      for (double& v : h.anchor_m)
        fields >> v;
      fields >> h.ki_Nm_A >> h.ri_ohm >> h.imax_A >> h.bv_Nms >> h.fc_Nm >> h.rotor_J_kgm2 >>
          h.volts;
      const int n = static_cast<int>(model.bodies.size());
      if (!fields || h.child < 0 || h.child >= n || h.parent < -1 || h.parent >= n)
        fail(table, line_no, "malformed hinge");
      model.hinges.push_back(h);
    } else {
      fail(table, line_no, "unknown line kind '" + kind + "'");
    }
  }
  return model;
}

std::vector<PileBody> read_pile(const std::filesystem::path& mjcf) {
  std::ifstream in = open(mjcf);
  std::vector<PileBody> bodies;
  int line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    const auto at = line.find("<body name=\"");
    if (at == std::string::npos) continue;
    PileBody b;
    const auto name_start = at + 12;
    b.name = line.substr(name_start, line.find('"', name_start) - name_start);
    const auto pos = attribute(line, "pos", mjcf, line_no);
    const auto quat = attribute(line, "quat", mjcf, line_no);
    const auto size = attribute(line, "size", mjcf, line_no);
    const auto mass = attribute(line, "mass", mjcf, line_no);
    b.sphere = line.find("type=\"sphere\"") != std::string::npos;
    if (pos.size() != 3 || quat.size() != 4 || mass.size() != 1 ||
        size.size() != (b.sphere ? 1u : 3u))
      fail(mjcf, line_no, "malformed body " + b.name);
    for (int i = 0; i < 3; ++i)
      b.position_m[i] = pos[i];
    for (int i = 0; i < 4; ++i)
      b.quat_wxyz[i] = quat[i];
    for (std::size_t i = 0; i < size.size(); ++i)
      b.half_size_m[i] = size[i];
    b.mass_kg = mass[0];
    bodies.push_back(b);
  }
  if (bodies.empty()) throw std::runtime_error(mjcf.string() + ": no <body> found");
  return bodies;
}

SpanningTree spanning_tree(const ArticulatedModel& model, const std::string& who) {
  const auto n = model.bodies.size();
  SpanningTree tree;
  tree.joint_of.assign(n, -1);
  std::vector<bool> placed(n, false);
  tree.fixed = std::any_of(model.hinges.begin(), model.hinges.end(),
                           [](const HingeSpec& h) { return h.parent < 0; });
  if (!tree.fixed && n > 0) placed[0] = true;
  for (bool grew = true; grew;) {
    grew = false;
    for (std::size_t k = 0; k < model.hinges.size(); ++k) {
      const HingeSpec& h = model.hinges[k];
      const auto child = static_cast<std::size_t>(h.child);
      const bool parent_placed = h.parent < 0 || placed[static_cast<std::size_t>(h.parent)];
      if (placed[child] || !parent_placed) continue;
      placed[child] = true;
      tree.joint_of[child] = static_cast<int>(k);
      tree.order.push_back(h.child);
      grew = true;
    }
  }
  if (std::count(placed.begin(), placed.end(), true) != static_cast<std::ptrdiff_t>(n))
    throw std::runtime_error(who + ": a body is not jointed to the tree");
  return tree;
}

}  // namespace peers
