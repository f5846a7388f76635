#include "scenario/did_you_mean.hpp"

#include <gtest/gtest.h>

namespace rumble::scenario {
namespace {

TEST(ScenarioDidYouMean, EditDistanceCountsTranspositionsAsOneEdit) {
  EXPECT_EQ(edit_distance("damping", "damping"), 0u);
  EXPECT_EQ(edit_distance("dampng", "damping"), 1u);
  EXPECT_EQ(edit_distance("wnikler", "winkler"), 1u);  // transposition
  EXPECT_EQ(edit_distance("wrinkler", "winkler"), 1u);
  EXPECT_EQ(edit_distance("E", "e"), 0u);  // case-insensitive
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
}

TEST(ScenarioDidYouMean, SuggestsOnlyPlausibleTypos) {
  const std::vector<std::string> soils = {"clm", "fem", "winkler"};
  EXPECT_EQ(closest_match("wrinkler", soils).value_or("-"), "winkler");
  EXPECT_EQ(closest_match("Winkler", soils).value_or("-"), "winkler");
  EXPECT_EQ(closest_match("clmm", soils).value_or("-"), "clm");
  EXPECT_FALSE(closest_match("finite_elements", soils).has_value());
  EXPECT_FALSE(closest_match("x", soils).has_value());
  EXPECT_FALSE(closest_match("x", {"E"}).has_value());  // not a typo: a different word
  EXPECT_EQ(closest_match("cc", {"c", "k"}).value_or("-"), "c");
  EXPECT_FALSE(closest_match("", soils).has_value());
  const std::vector<std::string> keys = {"rayleigh_alpha", "rayleigh_beta"};
  EXPECT_EQ(closest_match("rayleigh_alpah", keys).value_or("-"), "rayleigh_alpha");
  EXPECT_EQ(closest_match("mass_per_len", {"mass_per_length", "E"}).value_or("-"),
            "mass_per_length");
}

TEST(ScenarioDidYouMean, PrefersTheClosestAndDoesNotGuessBetweenEquals) {
  EXPECT_EQ(closest_match("deptth", {"depth", "dept"}).value_or("-"), "depth");
  EXPECT_FALSE(closest_match("FRA7", {"FRA1", "FRA2", "ISO3095"}).has_value());
  EXPECT_EQ(closest_match("FRA7", {"FRA1", "ISO3095"}).value_or("-"), "FRA1");
}

TEST(ScenarioDidYouMean, Join) {
  EXPECT_EQ(join({}), "");
  EXPECT_EQ(join({"a"}), "a");
  EXPECT_EQ(join({"a", "b", "c"}), "a, b, c");
}

}  // namespace
}  // namespace rumble::scenario
