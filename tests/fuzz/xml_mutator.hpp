#pragma once
/// \file
/// Deterministic, structure-aware mutations of a scene's XML text for the fuzzers: hostile
/// attribute values, dropped and duplicated elements, swapped attribute names, scaled numbers,
/// truncation and stray bytes. The same text and seed always give the same mutant, so every
/// finding is reproducible from (seed scene, case number).

#include <cstdint>
#include <string>

namespace s2sim::fuzz {

/// A small, fast generator (splitmix64): deterministic across platforms.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next();
  /// Uniform in [0, n); n > 0.
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(next() % n); }

 private:
  std::uint64_t state_;
};

/// What one mutation did, for the report ("value robot/solids/cuboid@mass -> 'nan'").
struct Mutation {
  std::string text;         ///< the mutated document
  std::string description;  ///< one line
};

/// Applies one randomly chosen mutation to `xml`. A document with nothing the chosen kind can
/// act on falls back to a byte-level mutation, so the result always differs from the input
/// unless the input is empty.
Mutation mutate(const std::string& xml, Rng& rng);

}  // namespace s2sim::fuzz
