// The state layout: named segments, a layout id, save and checked restore.
#include "common/state_layout.hpp"

#include <s2sim/error.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

namespace s2sim::common {
namespace {

std::string size_text(const StateLayout::Entry& e) {
  return e.size == StateLayout::kVariable ? std::to_string(e.unit) + "*n" : std::to_string(e.size);
}

}  // namespace

void StateLayout::add(std::string name, std::size_t size, Save save, Restore restore) {
  const std::size_t n = size;
  add_variable(
      std::move(name), 1, [n] { return n; }, std::move(save), std::move(restore));
  entries_.back().size = size;
  entries_.back().unit = 1;
  id_ = id_of(entries_);
}

void StateLayout::add_variable(std::string name, std::size_t unit, Count count, Save save,
                               Restore restore) {
  for (const Entry& e : entries_)
    if (e.name == name)
      throw Error(ErrorKind::runtime, "state segment '" + name + "' registered twice");
  entries_.push_back({std::move(name), kVariable, std::max<std::size_t>(unit, 1)});
  segments_.push_back({std::move(count), std::move(save), std::move(restore)});
  id_ = id_of(entries_);
}

std::uint64_t StateLayout::id_of(const std::vector<Entry>& entries) {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&h](const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) {
      h ^= p[i];
      h *= 1099511628211ull;
    }
  };
  for (const Entry& e : entries) {
    mix(e.name.data(), e.name.size() + 1);  // with its terminator: "a","bc" != "ab","c"
    const std::uint64_t size = e.size, unit = e.unit;
    mix(&size, sizeof size);
    mix(&unit, sizeof unit);
  }
  return h;
}

std::string StateLayout::describe(const std::vector<Entry>& entries) {
  std::string out;
  for (const Entry& e : entries)
    out += (out.empty() ? "" : ", ") + e.name + "[" + size_text(e) + "]";
  return out;
}

void StateLayout::save(std::vector<double>& out) const {
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    const Segment& s = segments_[i];
    const std::size_t n = s.count();
    if (entries_[i].size == kVariable) out.push_back(static_cast<double>(n));
    const std::size_t at = out.size();
    out.resize(at + n);
    if (n > 0) s.save(out.data() + at);
  }
}

std::vector<StateLayout::Range> StateLayout::locate(const std::vector<Entry>& entries,
                                                    const std::vector<double>& values) {
  std::vector<Range> ranges;
  std::size_t k = 0;
  auto fail = [&](const std::string& why) {
    throw Error(ErrorKind::usage, "malformed snapshot: " + why);
  };
  for (const Entry& e : entries) {
    std::size_t n = e.size;
    if (e.size == kVariable) {
      if (k >= values.size()) fail("segment '" + e.name + "' has no count");
      const double count = values[k++];
      if (!(count >= 0) || count != std::floor(count) ||
          count > static_cast<double>(values.size() - k))
        fail("segment '" + e.name + "' has an impossible count " + std::to_string(count));
      n = static_cast<std::size_t>(count);
      if (n % e.unit != 0)
        fail("segment '" + e.name + "' holds " + std::to_string(n) +
             " numbers, not a multiple of " + std::to_string(e.unit));
    }
    if (n > values.size() - k)
      fail("segment '" + e.name + "' runs past the end (" + std::to_string(values.size()) +
           " numbers)");
    ranges.push_back({k, n});
    k += n;
  }
  if (k != values.size())
    fail(std::to_string(values.size() - k) + " numbers after the last segment");
  return ranges;
}

void StateLayout::restore(std::uint64_t id, const std::vector<Entry>& entries,
                          const std::vector<double>& values) const {
  if (id != id_ || id_of(entries) != id_) {
    // Name the first segment that differs.
    std::string why;
    const std::size_t n = std::min(entries.size(), entries_.size());
    for (std::size_t i = 0; i < n && why.empty(); ++i) {
      const Entry &theirs = entries[i], &ours = entries_[i];
      if (theirs.name != ours.name)
        why = "segment " + std::to_string(i + 1) + " is '" + theirs.name + "' there, '" +
              ours.name + "' here";
      else if (theirs.size != ours.size || theirs.unit != ours.unit)
        why = "segment '" + ours.name + "' holds " + size_text(theirs) + " numbers there, " +
              size_text(ours) + " here";
    }
    if (why.empty() && entries.size() > n)
      why = "it has a segment '" + entries[n].name + "' this simulation does not";
    if (why.empty() && entries_.size() > n)
      why = "it lacks this simulation's segment '" + entries_[n].name + "'";
    if (why.empty()) why = "its layout id does not match its segments";
    throw Error(ErrorKind::usage, "snapshot from another simulation (state layout " +
                                      std::to_string(id) + ", this one " + std::to_string(id_) +
                                      "): " + why);
  }
  const std::vector<Range> ranges = locate(entries_, values);
  for (std::size_t i = 0; i < segments_.size(); ++i)
    segments_[i].restore(values.data() + ranges[i].offset, ranges[i].size);
}

}  // namespace s2sim::common
