// Unevenness built from track.unevenness: the random type end to end, and the exact text of
// every input error (each names the key's JSON pointer).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <vector>

#include "expect_message.hpp"
#include "track/unevenness.hpp"

namespace rumble {
namespace {

using nlohmann::json;
using test::expect_invalid_argument;
const std::vector<double> kInputRadii = {0.46, 0.46};

json random_spec(const char* cls, unsigned seed, double lmin, double lmax) {
  return {{"type", "random"},
          {"class", cls},
          {"seed", seed},
          {"wavelength_min", lmin},
          {"wavelength_max", lmax}};
}

TEST(UnevennessRandom, SameSeedSameProfileDifferentSeedDifferent) {
  const Unevenness a(random_spec("FRA4", 7, 1.0, 30.0), kInputRadii, -0.6, 120.0);
  const Unevenness b(random_spec("FRA4", 7, 1.0, 30.0), kInputRadii, -0.6, 120.0);
  const Unevenness c(random_spec("FRA4", 8, 1.0, 30.0), kInputRadii, -0.6, 120.0);
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
  const Unevenness u(random_spec("ISO3095", 3, 0.01, 0.3), kInputRadii, 0.0, 20.0);
  double ms = 0.0;
  int n = 0;
  for (double x = 0.0; x < 20.0; x += 1e-3, ++n) ms += u.at(0, x, 0.0) * u.at(0, x, 0.0);
  // ISO 3095 limit between 1 and 30 cm: tens of micrometres rms at most.
  EXPECT_GT(std::sqrt(ms / n), 1e-6);
  EXPECT_LT(std::sqrt(ms / n), 2e-5);
}

TEST(UnevennessInput, ShapesRejectMissingOrBadValues) {
  expect_invalid_argument(
      [] {
        Unevenness(json{{"type", "dip"}, {"position", 1.0}, {"length", 0.3}}, kInputRadii, 0, 10);
      },
      "/track/unevenness/depth: required for type 'dip'");
  expect_invalid_argument(
      [] {
        Unevenness(json{{"type", "bump"}, {"position", 1.0}, {"length", 0.0}, {"height", 1e-3}},
                   kInputRadii, 0, 10);
      },
      "/track/unevenness/length: must be > 0 m, got 0");
  expect_invalid_argument(
      [] {
        Unevenness(json{{"type", "dip"}, {"position", "a"}, {"length", 1.0}, {"depth", 1e-3}},
                   kInputRadii, 0, 10);
      },
      "/track/unevenness/position: must be a number, got \"a\"");
  expect_invalid_argument(
      [] {
        Unevenness(json{{"type", "wave"}}, kInputRadii, 0, 10);
      },
      "/track/unevenness/type: unknown type \"wave\"; use none, dip, bump, "
      "wheel_flat or random");
}

TEST(UnevennessInput, WheelFlatRejectsBadWheelLengthAndPhase) {
  expect_invalid_argument(
      [] {
        Unevenness(json{{"type", "wheel_flat"}, {"length", 0.05}, {"wheel", 2}}, kInputRadii, 0,
                   10);
      },
      "/track/unevenness/wheel: wheel 2 does not exist; the vehicles have 2 wheel(s), numbered "
      "from 0");
  expect_invalid_argument(
      [] {
        Unevenness(json{{"type", "wheel_flat"}, {"length", 3.0}}, kInputRadii, 0, 10);
      },
      "/track/unevenness/length: a flat of 3 m does not fit on a wheel of circumference 2.89027 m");
  expect_invalid_argument(
      [] {
        Unevenness(json{{"type", "wheel_flat"}, {"length", 0.05}, {"first_impact", 3.0}},
                   kInputRadii, 0, 10);
      },
      "/track/unevenness/first_impact: must be in [0, 2 pi R) = [0, 2.89027) m, got 3");
  expect_invalid_argument(
      [] {
        Unevenness(json{{"type", "wheel_flat"}, {"length", 0.05}, {"depth", -1e-4}}, kInputRadii, 0,
                   10);
      },
      "/track/unevenness/depth: must be > 0 m, got -0.0001");
}

TEST(UnevennessInput, RandomRejectsBadClassSeedAndBand) {
  expect_invalid_argument(
      [] { Unevenness(random_spec("FRA7", 1, 1.0, 30.0), kInputRadii, 0, 100); },
      "/track/unevenness/class: unknown roughness spectrum 'FRA7'; use FRA1 .. FRA6 or ISO3095");
  expect_invalid_argument(
      [] {
        json spec = random_spec("FRA1", 1, 1.0, 30.0);
        spec["seed"] = -1;
        Unevenness(spec, kInputRadii, 0, 100);
      },
      "/track/unevenness/seed: must be an integer >= 0, got -1");
  expect_invalid_argument(
      [] { Unevenness(random_spec("FRA1", 1, 30.0, 1.0), kInputRadii, 0, 100); },
      "/track/unevenness/wavelength_max: must be > wavelength_min = 30 m, got "
      "1 m");
  expect_invalid_argument(
      [] { Unevenness(random_spec("ISO3095", 1, 1.0, 30.0), kInputRadii, 0, 100); },
      "/track/unevenness: random profile: the ISO3095 spectrum is defined for wavelengths from "
      "0.00281838 m to 0.446684 m, got 1 m to 30 m");
  expect_invalid_argument(
      [] { Unevenness(random_spec("FRA1", 1, 0.001, 30.0), kInputRadii, 0, 1000); },
      "/track/unevenness: random profile: 1000 m at a spacing of wavelength_min/16 = 6.25e-05 m "
      "needs 1.6e+07 points, more than 4194304; raise wavelength_min, lower wavelength_max or "
      "shorten the track");
  expect_invalid_argument([] { Unevenness(random_spec("FRA1", 1, 1.0, 30.0), kInputRadii, 5, 5); },
                          "/track/unevenness: random profile: the track span [5, 5] m is empty");
}

}  // namespace
}  // namespace rumble
