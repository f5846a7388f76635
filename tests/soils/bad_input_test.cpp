// What the schema cannot express, or what a direct caller of the C API could still get wrong:
// refused with std::invalid_argument (RUMBLE_ERROR) and a message saying what, the offending
// value and the fix. Messages are checked word for word: they are the user interface.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <numbers>

#include "soil_cases.hpp"
#include "soil_harness.hpp"

namespace rumble::test {
namespace {

const std::string kMedium = soil_params(kSoils[1]).dump();
const std::string kChainTail =
    "; the chain couples each footprint to its neighbours at one spacing (use winkler for other "
    "layouts)";

std::string layout_error(const std::string& type, const std::string& params,
                         const std::vector<rumble_footprint>& footprints) {
  TestSoil soil(type, params);
  std::string message;
  EXPECT_EQ(soil.try_accept_layout(footprints, &message), RUMBLE_ERROR);
  return message;
}

TEST(SoilBadInput, ClmRefusesUnequalSpacing) {
  auto row = sleeper_row(12);
  row[7].x = 4.5;
  EXPECT_EQ(layout_error("clm", kMedium, row),
            "clm: footprints must be equally spaced along the track; footprint 7 is at x = 4.5 m, "
            "expected 4.2 m (spacing 0.6 m)" +
                kChainTail);
}

TEST(SoilBadInput, ClmRefusesOtherChainLayouts) {
  auto reversed = sleeper_row(3);
  std::swap(reversed[0].x, reversed[2].x);
  EXPECT_EQ(layout_error("clm", kMedium, reversed),
            "clm: footprints must be in order of increasing x along the track; footprint 1 is at "
            "x = 0.6 m, footprint 0 at x = 1.2 m" +
                kChainTail);
  auto off_line = sleeper_row(6);
  off_line[3].y = 0.75;
  EXPECT_EQ(layout_error("clm", kMedium, off_line),
            "clm: footprints must lie on one line along the track; footprint 3 is at y = 0.75 m, "
            "footprint 0 at y = 0 m" +
                kChainTail);
  auto sizes = sleeper_row(6);
  sizes[4].length = 2.5;
  EXPECT_EQ(layout_error("clm", kMedium, sizes),
            "clm: footprints must all have the size of footprint 0 (2.6 m x 0.26 m) to be "
            "calibrated from soil properties; footprint 4 is 2.5 m x 0.26 m" +
                kChainTail);
  // Given parameters do not depend on the size: accepted.
  TestSoil direct("clm", R"({"m_f": 0, "k_f": 1e8, "c_f": 1e5, "k_c": 5e7, "c_c": 5e4})");
  EXPECT_EQ(direct.try_accept_layout(sizes, nullptr), RUMBLE_OK);
  EXPECT_EQ(layout_error("clm", kMedium, sleeper_row(5, 0.2)),
            "clm: footprints overlap: the spacing 0.2 m is less than their width 0.26 m along the "
            "track; calibrating from soil properties needs footprints that do not overlap");
}

TEST(SoilBadInput, RefusesEmptyOrSizelessLayouts) {
  EXPECT_EQ(layout_error("winkler", kMedium, {}), "winkler: the layout has no footprints");
  auto row = sleeper_row(4);
  row[2].width = 0.0;
  EXPECT_EQ(layout_error("winkler", kMedium, row),
            "winkler: footprint 2 is 2.6 m x 0 m; deriving k, c, m from soil properties needs a "
            "length and width > 0");
}

TEST(SoilBadInput, ParameterRanges) {
  EXPECT_EQ(creation_error("winkler", R"({"k": -1, "c": 0})"),
            "winkler: params/k: must be > 0 N/m, got -1");
  EXPECT_EQ(creation_error("winkler", R"({"k": 1e8, "c": -5})"),
            "winkler: params/c: must be >= 0 N s/m, got -5");
  EXPECT_EQ(creation_error("clm", R"({"m_f": 0, "k_f": 0, "c_f": 1, "k_c": 1, "c_c": 1})"),
            "clm: params/k_f: must be > 0 N/m, got 0");
  EXPECT_EQ(creation_error("clm", R"({"m_f": 10, "k_f": 1e8, "c_f": 1, "k_c": -2, "c_c": 1})"),
            "clm: params/k_c: must be >= 0 N/m, got -2");
  EXPECT_EQ(creation_error("winkler", R"({"E": 1e8, "nu": 0.5, "rho": 1800})"),
            "winkler: params/nu: Poisson ratio must be in [0, 0.5), got 0.5");
  EXPECT_EQ(creation_error("clm", R"({"E": 1e8, "nu": -0.1, "rho": 1800})"),
            "clm: params/nu: Poisson ratio must be in [0, 0.5), got -0.1");
  EXPECT_EQ(creation_error("clm", R"({"E": 0, "nu": 0.3, "rho": 1800})"),
            "clm: params/E: Young's modulus must be > 0 Pa, got 0");
  EXPECT_EQ(creation_error("winkler", R"({"E": 1e8, "nu": 0.3, "rho": 0})"),
            "winkler: params/rho: density must be > 0 kg/m^3, got 0");
  EXPECT_EQ(creation_error("clm", R"({"E": 1e8, "nu": 0.3, "rho": 1800, "max_step": 0})"),
            "clm: params/max_step: must be > 0 s, got 0");
  EXPECT_EQ(creation_error("clm", R"({"E": 1e8, "nu": 0.3, "rho": 1800,
                                      "layers": [{"thickness": 0, "E": 1e7, "nu": 0.3, "rho": 1600}]})"),
            "clm: params/layers/0/thickness: must be > 0 m, got 0");
  EXPECT_EQ(creation_error("winkler", R"({"E": 1e8, "nu": 0.3, "rho": 1800,
                                          "layers": [{"thickness": 1, "E": 1e7, "nu": 0.3, "rho": 1600},
                                                     {"thickness": 1, "E": 1e7, "nu": 0.6, "rho": 1600}]})"),
            "winkler: params/layers/1/nu: Poisson ratio must be in [0, 0.5), got 0.6");
}

TEST(SoilBadInput, DirectOrFromSoilNotBoth) {
  EXPECT_EQ(creation_error("winkler", R"({"k": 1e8, "c": 1e5, "E": 1e8, "nu": 0.3, "rho": 1800})"),
            "winkler: give either k and c (direct), or E, nu and rho (from soil properties), not "
            "both; got k and c with E, nu and rho");
  EXPECT_EQ(creation_error("clm", R"({"m_f": 0, "k_f": 1e8, "c_f": 1, "k_c": 1, "c_c": 1,
                                      "layers": []})"),
            "clm: give either m_f, k_f, c_f, k_c and c_c (direct), or E, nu and rho (from soil "
            "properties), not both; got k_f, c_f, k_c and c_c with layers");
  EXPECT_EQ(creation_error("winkler", R"({"m": 10})"),
            "winkler: give either k and c (direct), or E, nu and rho (from soil properties); got "
            "neither");
}

TEST(SoilBadInput, ClmMasslessChainNeedsAGroundDashpot) {
  EXPECT_EQ(
      creation_error("clm", R"({"m_f": 0, "k_f": 1e8, "c_f": 0, "k_c": 5e7, "c_c": 5e4})"),
      "clm: with m_f = 0 and c_c > 0 the ground dashpot c_f must be > 0, got 0; give m_f > 0, "
      "c_f > 0 or c_c = 0");
}

TEST(SoilBadInput, CallsOutOfOrderOrOutOfRange) {
  TestSoil soil("winkler", R"({"k": 1e8, "c": 1e5})");
  std::string message;
  EXPECT_EQ(soil.try_advance(0.0, 1e-3, 0, VectorXd::Zero(1), &message), RUMBLE_ERROR);
  EXPECT_EQ(message, "winkler: advance called before accept_layout");
  soil.accept_layout(sleeper_row(1));
  EXPECT_EQ(soil.try_advance(0.0, 0.0, 0, VectorXd::Zero(1), &message), RUMBLE_ERROR);
  EXPECT_EQ(message, "winkler: macro step H must be > 0 s, got 0");
}

TEST(SoilBadInput, UndampedResonanceIsReportedNotReturnedAsInfinity) {
  const double f = 10.0, m = 100.0, w = 2.0 * std::numbers::pi * f;
  TestSoil soil("winkler", nlohmann::json({{"k", w * w * m}, {"c", 0.0}, {"m", m}}).dump());
  soil.accept_layout(sleeper_row(1));
  double re = 0.0, im = 0.0;
  EXPECT_EQ(soil.api().frequency_response(soil.self(), f, &re, &im, 1), RUMBLE_ERROR);
  EXPECT_STREQ(soil.api().common.last_message(soil.self()),
               "winkler: the dynamic stiffness is singular at f = 10 Hz (an undamped resonance)");
}

}  // namespace
}  // namespace rumble::test
