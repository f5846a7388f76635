// Unevenness built from a validated track.unevenness: the random type end to end, and the exact
// text of every error of a relation the schema cannot state (each names the key's JSON pointer);
// the schema's own refusals are tested with validation (tests/scenario/validate_test.cpp).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <vector>

#include "expect_message.hpp"
#include "scenario/scenario_schema.hpp"
#include "track/unevenness.hpp"

namespace rumble {
namespace {

using nlohmann::json;
using test::expect_invalid_argument;
const std::vector<double> kInputRadii = {0.46, 0.46};

/// The profile of a /track/unevenness as validation hands it over (defaults filled).
Unevenness unevenness(const json& spec, const std::vector<double>& radii, double x_min,
                      double x_max) {
  return Unevenness(UnevennessSpec::from_json(scenario::unevenness_with_defaults(spec)), radii,
                    x_min, x_max);
}

json random_spec(const char* cls, unsigned seed, double lmin, double lmax) {
  return {{"type", "random"},
          {"class", cls},
          {"seed", seed},
          {"wavelength_min", lmin},
          {"wavelength_max", lmax}};
}

TEST(UnevennessRandom, SameSeedSameProfileDifferentSeedDifferent) {
  const Unevenness a = unevenness(random_spec("FRA4", 7, 1.0, 30.0), kInputRadii, -0.6, 120.0);
  const Unevenness b = unevenness(random_spec("FRA4", 7, 1.0, 30.0), kInputRadii, -0.6, 120.0);
  const Unevenness c = unevenness(random_spec("FRA4", 8, 1.0, 30.0), kInputRadii, -0.6, 120.0);
  double sum_a = 0.0, sum_diff = 0.0;
  for (double x = -0.6; x <= 120.0; x += 0.0137) {
    EXPECT_EQ(a.at(0, x, 0.0), b.at(0, x, 0.0)) << x;   // bit for bit
    EXPECT_EQ(a.at(0, x, 0.0), a.at(1, x, 55.0)) << x;  // a rail profile: any wheel, any roll
    sum_a += a.at(0, x, 0.0) * a.at(0, x, 0.0);
    sum_diff += (a.at(0, x, 0.0) - c.at(0, x, 0.0)) * (a.at(0, x, 0.0) - c.at(0, x, 0.0));
  }
  // Independent profiles: E[(a - c)^2] = 2 E[a^2]. Over 120 m of a spectrum dominated by its
  // 30 m waves the ratio scatters a lot; below 0.2 would mean strongly correlated profiles.
  EXPECT_GT(sum_diff, 0.2 * sum_a);
}

TEST(UnevennessRandom, Iso3095ClassBuildsAShortWaveProfile) {
  const Unevenness u = unevenness(random_spec("ISO3095", 3, 0.01, 0.3), kInputRadii, 0.0, 20.0);
  double ms = 0.0;
  int n = 0;
  for (double x = 0.0; x < 20.0; x += 1e-3, ++n) ms += u.at(0, x, 0.0) * u.at(0, x, 0.0);
  // ISO 3095 limit between 1 and 30 cm: tens of micrometres rms at most.
  EXPECT_GT(std::sqrt(ms / n), 1e-6);
  EXPECT_LT(std::sqrt(ms / n), 2e-5);
}

TEST(UnevennessInput, WheelFlatRejectsBadWheelLengthAndPhase) {
  expect_invalid_argument(
      [] {
        unevenness(json{{"type", "wheel_flat"}, {"length", 0.05}, {"wheel", 2}}, kInputRadii, 0,
                   10);
      },
      "/track/unevenness/wheel: wheel 2 does not exist; the vehicles have 2 wheel(s), numbered "
      "from 0");
  expect_invalid_argument(
      [] {
        unevenness(json{{"type", "wheel_flat"}, {"length", 3.0}}, kInputRadii, 0, 10);
      },
      "/track/unevenness/length: a flat of 3 m does not fit on a wheel of circumference 2.89027 m");
  expect_invalid_argument(
      [] {
        unevenness(json{{"type", "wheel_flat"}, {"length", 0.05}, {"first_impact", 3.0}},
                   kInputRadii, 0, 10);
      },
      "/track/unevenness/first_impact: must be in [0, 2 pi R) = [0, 2.89027) m, got 3");
}

TEST(UnevennessInput, RandomRejectsABandOutsideItsSpectrumOrASpanItCannotCover) {
  expect_invalid_argument(
      [] { unevenness(random_spec("FRA1", 1, 30.0, 1.0), kInputRadii, 0, 100); },
      "/track/unevenness/wavelength_max: must be > wavelength_min = 30 m, got "
      "1 m");
  expect_invalid_argument(
      [] { unevenness(random_spec("ISO3095", 1, 1.0, 30.0), kInputRadii, 0, 100); },
      "/track/unevenness/wavelength_max: the ISO3095 spectrum is defined for wavelengths from "
      "0.00281838 m to 0.446684 m, got 30 m");
  expect_invalid_argument(
      [] { unevenness(random_spec("FRA1", 1, 0.001, 30.0), kInputRadii, 0, 1000); },
      "/track/unevenness: random profile: 1000 m at a spacing of wavelength_min/16 = 6.25e-05 m "
      "needs 1.6e+07 points, more than 4194304; raise wavelength_min, lower wavelength_max or "
      "shorten the track");
  expect_invalid_argument([] { unevenness(random_spec("FRA1", 1, 1.0, 30.0), kInputRadii, 5, 5); },
                          "/track/unevenness: random profile: the track span [5, 5] m is empty");
}

}  // namespace
}  // namespace rumble
