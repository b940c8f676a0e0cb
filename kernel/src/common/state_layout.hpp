#pragma once
/// \file
/// The state layout: what a snapshot holds, declared rather than serialised by hand. At load,
/// each subsystem (multibody, loose bodies, contact, the façade's buffers) registers named
/// segments of numbers with the functions that copy them out and back; a snapshot is the
/// layout's id (a hash of the segment names and sizes) and one buffer with the segments one
/// after another (docs/scheduling.md, "Snapshots"). No Simbody here; C++17-clean, since
/// model/ (compiled as C++17) registers its segments through it.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace s2sim::common {

class StateLayout {
 public:
  /// The size of a segment whose length changes while running (contact memory): the buffer
  /// holds its count of numbers first.
  static constexpr std::size_t kVariable = static_cast<std::size_t>(-1);

  /// Writes the segment's numbers to `out` (its size, or count() for a variable segment).
  using Save = std::function<void(double* out)>;
  /// Reads `count` numbers back from `in` (count = size for a fixed segment).
  using Restore = std::function<void(const double* in, std::size_t count)>;
  using Count = std::function<std::size_t()>;

  /// A segment's name and size (kVariable) and, for a variable one, the numbers per element
  /// (its count must be a multiple).
  struct Entry {
    std::string name;
    std::size_t size = 0;
    std::size_t unit = 1;
  };
  /// Where a segment lies in a buffer (a variable one: after its count).
  struct Range {
    std::size_t offset = 0, size = 0;
  };

  /// A segment of `size` numbers, fixed at load. Throws s2sim::Error (runtime) for a name
  /// already registered.
  void add(std::string name, std::size_t size, Save save, Restore restore);
  /// A segment of `count()` numbers, a multiple of `unit`, that changes while running.
  void add_variable(std::string name, std::size_t unit, Count count, Save save, Restore restore);

  const std::vector<Entry>& entries() const { return entries_; }
  /// FNV-1a over the segment names, sizes and units, in order.
  std::uint64_t id() const { return id_; }
  static std::uint64_t id_of(const std::vector<Entry>& entries);

  /// Every segment, in order, appended to `out` (may allocate).
  void save(std::vector<double>& out) const;
  /// Checks that `id` and `entries` (a snapshot's) are this layout's and that `values` holds
  /// exactly its segments, then copies each segment back. Throws s2sim::Error (usage) naming
  /// the first mismatch before changing anything.
  void restore(std::uint64_t id, const std::vector<Entry>& entries,
               const std::vector<double>& values) const;

  /// Each segment's place in `values`, a buffer of `entries` (checked: usage error).
  static std::vector<Range> locate(const std::vector<Entry>& entries,
                                   const std::vector<double>& values);
  /// "multibody/q[7], contact/memory[8*n], ...".
  static std::string describe(const std::vector<Entry>& entries);

 private:
  struct Segment {
    Count count;
    Save save;
    Restore restore;
  };
  std::vector<Entry> entries_;
  std::vector<Segment> segments_;
  std::uint64_t id_ = id_of({});
};

}  // namespace s2sim::common
