// The mutator the fuzzers rely on: reproducible from its seed, and each case really mutates.
#include "xml_mutator.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace s2sim::fuzz {
namespace {

const std::string kScene =
    "<?xml version='1.0'?>\n<scene>\n  <robot>\n    <ID name='bot'/>\n"
    "    <pos x='0' y='0' z='0.1'/>\n    <body file='bot.xml'/>\n  </robot>\n</scene>\n";

TEST(XmlMutator, TheSameSeedGivesTheSameMutantAndEveryMutantDiffers) {
  std::set<std::string> kinds;
  for (std::uint64_t seed = 0; seed < 500; ++seed) {
    Rng a(seed), b(seed);
    const Mutation ma = mutate(kScene, a), mb = mutate(kScene, b);
    EXPECT_EQ(ma.text, mb.text) << seed;
    EXPECT_EQ(ma.description, mb.description) << seed;
    EXPECT_NE(ma.text, kScene) << seed << ": " << ma.description;
    kinds.insert(ma.description.substr(0, ma.description.find(' ')));
  }
  // Values, scaled values, dropped and duplicated elements, renamed attributes, truncation,
  // stray bytes and deep nesting all occur.
  for (const char* kind : {"value", "dropped", "duplicated", "attribute", "truncated", "stray"})
    EXPECT_TRUE(kinds.count(kind)) << kind;
  bool nested = false;
  for (const auto& k : kinds)
    nested = nested || k.find_first_not_of("0123456789") == std::string::npos;
  EXPECT_TRUE(nested) << "no deep nesting among 500 cases";
}

TEST(XmlMutator, HostileValuesReplaceAttributeValuesInPlace) {
  int replaced = 0;
  for (std::uint64_t seed = 0; seed < 200; ++seed) {
    Rng rng(seed);
    const Mutation m = mutate(kScene, rng);
    if (m.description.rfind("value ", 0) != 0) continue;
    ++replaced;
    // Everything outside the value is untouched: the declaration, the document's opening and
    // closing elements.
    EXPECT_EQ(m.text.substr(0, 30), kScene.substr(0, 30)) << m.description;
    EXPECT_EQ(m.text.substr(m.text.size() - 20), kScene.substr(kScene.size() - 20));
  }
  EXPECT_GT(replaced, 20);
}

TEST(XmlMutator, AnEmptyDocumentStaysEmpty) {
  Rng rng(3);
  EXPECT_EQ(mutate("", rng).text, "");
}

}  // namespace
}  // namespace s2sim::fuzz
