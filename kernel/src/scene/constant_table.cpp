/// \file
/// ConstantTable: the constants of one `<defines>` scope (simtwo-format.md §2.1). Tables hold a
/// few dozen entries at most, so a linear search over upper-cased names is enough.

#include <s2sim/kernel/scene.hpp>

#include <string>
#include <string_view>
#include <utility>

namespace s2sim::scene {
namespace {

// ASCII only: names are letters, digits and '_'; the locale must not change matching.
std::string upper(std::string_view name) {
  std::string out(name);
  for (char& c : out)
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  return out;
}

}  // namespace

void ConstantTable::set(std::string_view name, double value) {
  std::string key = upper(name);
  for (auto& [k, v] : entries_) {
    if (k == key) {
      v = value;
      return;
    }
  }
  entries_.emplace_back(std::move(key), value);
}

bool ConstantTable::define_if_absent(std::string_view name, double value) {
  std::string key = upper(name);
  for (const auto& entry : entries_)
    if (entry.first == key) return false;
  entries_.emplace_back(std::move(key), value);
  return true;
}

void ConstantTable::declare(std::string_view name, bool arg) {
  declared_->push_back({std::string(name), arg});
}

std::optional<double> ConstantTable::find(std::string_view name) const {
  const std::string key = upper(name);
  for (const auto& [k, v] : entries_)
    if (k == key) return v;
  return std::nullopt;
}

}  // namespace s2sim::scene
