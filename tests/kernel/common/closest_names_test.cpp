// "Did you mean" (kernel/src/common/closest_names.hpp): the edit distance, the closest names in
// order with ties by name, and the message built from them.
#include "common/closest_names.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace s2sim::common {
namespace {

TEST(ClosestNames, EditDistanceCountsInsertionsDeletionsAndReplacements) {
  EXPECT_EQ(edit_distance("", ""), 0u);
  EXPECT_EQ(edit_distance("abc", "abc"), 0u);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("abc", "ab"), 1u);
}

TEST(ClosestNames, TheClosestComeFirstAndTiesGoByName) {
  const std::vector<std::string> names = {"servo", "sensor", "motor", "serve", "dc_motor"};
  EXPECT_EQ(closest_names("servo", names, 3),
            (std::vector<std::string>{"servo", "serve", "sensor"}));
  EXPECT_EQ(closest_names("motr", names, 1), (std::vector<std::string>{"motor"}));
  EXPECT_EQ(closest_names("x", {}, 3), std::vector<std::string>{});
  EXPECT_EQ(closest_names("x", names, 9).size(), names.size());
}

TEST(ClosestNames, TheMessageNamesTheUnknownAndItsNeighbours) {
  EXPECT_EQ(unknown_name_message("signal", "tim", {"time", "contacts/count"}),
            "unknown signal 'tim'; did you mean 'time', 'contacts/count'?");
  EXPECT_EQ(unknown_name_message("input", "a", {}), "unknown input 'a'");
}

}  // namespace
}  // namespace s2sim::common
