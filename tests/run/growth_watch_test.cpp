// GrowthWatch (run/growth_watch.hpp): a footprint speed that grows at one exponential rate past
// twice anything before is caught with its rate per macro step (within 3 windows when it flips
// sign every step, as an unstable explicit coupling over a massless soil does; after 60 ms of
// rising otherwise); what a passing train does (a start from rest, a dip's blow that rings down,
// a steady ripple) is not, nor the motion under a prescribed load rising from rest.
#include "run/growth_watch.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <optional>
#include <utility>

namespace rumble {
namespace {

using Signal = std::function<double(double)>;

/// Feeds speed(t) with the alternating part alternating(t) at macro steps of H [s] up to t_end
/// [s]; returns the first growth seen and the time it was seen.
std::optional<std::pair<Growth, double>> watch(const Signal& speed, const Signal& alternating,
                                               double H, double t_end) {
  GrowthWatch w;
  const long steps = std::lround(t_end / H);
  for (long k = 1; k <= steps; ++k) {
    const double t = static_cast<double>(k) * H;
    if (auto g = w.add(t, H, speed(t), alternating(t))) return std::make_pair(*g, t);
  }
  return std::nullopt;
}

const Signal kSmooth = [](double) { return 0.0; };

/// A train's motion: 8 mm/s with a ripple at 41.7 Hz (sleeper passing at 25 m/s).
double train(double t) {
  return 8e-3 * (1.0 + 0.3 * std::abs(std::sin(2.0 * M_PI * 41.7 * t)));
}

TEST(GrowthWatch, CatchesTheUnstableCouplingOfIssue29EarlyWithItsRate) {
  // Gauss-Seidel over a massless CLM at H = 0.5 ms: 1.03 per macro step (doubling every
  // 11.7 ms), its sign flipping every step, from rounding-level motion under the train's 8 mm/s.
  const double H = 5e-4, rho = 1.03;
  const Signal mode = [&](double t) { return 1e-6 * std::pow(rho, t / H); };
  const Signal speed = [&](double t) { return train(t) + mode(t); };
  const auto seen = watch(speed, mode, H, 0.25);
  ASSERT_TRUE(seen.has_value());
  EXPECT_NEAR(seen->first.per_step, rho, 0.005);
  EXPECT_NEAR(seen->first.doubling_s, H * std::log(2.0) / std::log(rho), 2e-3);
  EXPECT_LT(speed(seen->second), 0.06);  // m/s: long before any size bound
  EXPECT_GE(seen->first.peak, 2.0 * seen->first.peak_before);
}

TEST(GrowthWatch, CatchesASmoothSlowGrowthThatASizeBoundMisses) {
  // 1.0067 per step at 1 ms (the soft soil's Gauss-Seidel, docs/couplers.md): 28x in 0.5 s.
  const double H = 1e-3, rho = 1.0067;
  const auto seen =
      watch([&](double t) { return train(t) + 1e-3 * std::pow(rho, t / H); }, kSmooth, H, 0.5);
  ASSERT_TRUE(seen.has_value());
  EXPECT_NEAR(seen->first.per_step, rho, 0.003);
}

TEST(GrowthWatch, LeavesAStartFromRestADipAndASteadyTrainAlone) {
  for (double H : {1e-4, 5e-4, 1e-3}) {
    // Rising from rest over 20 ms to the train's motion.
    EXPECT_FALSE(
        watch([](double t) { return train(t) * (1.0 - std::exp(-t / 0.02)); }, kSmooth, H, 1.0))
        << H;
    // A dip at 0.4 s over a smooth track: a blow of 40x rising exponentially over 30 ms,
    // ringing down over 30 ms.
    const Signal dip = [](double t) {
      const double s = t - 0.4, rise = 0.03;
      const double blow = s < 0.0    ? 0.0
                          : s < rise ? std::expm1(s / rise * std::log(40.0)) / 39.0
                                     : std::exp(-(s - rise) / 0.03);
      return 3e-4 * (1.0 + 39.0 * blow);
    };
    EXPECT_FALSE(watch(dip, kSmooth, H, 1.0)) << H;
    // Rounding noise of a soil at rest, even if it drifts up.
    EXPECT_FALSE(watch([](double t) { return 1e-12 * std::exp(10.0 * t); }, kSmooth, H, 1.0)) << H;
  }
}

TEST(GrowthWatch, LeavesALoadThatRisesFromRestAndRingsDownAlone) {
  // A prescribed load on a soil with no static load (docs/couplers.md, "No static load"): the
  // footprints are at rest until the load starts at t0, so nothing came before to be twice of,
  // and a slow load rises for longer than 60 ms. The speed follows the load's rate: a smooth
  // ramp (1 - cos over T) moves it as sin(pi s / T), a Hann pulse as |sin(2 pi s / T)|; after
  // the load it rings down. Each was taken for growth before the steady-rate check (T >= 0.15 s
  // and >= 0.3 s).
  const double pi = std::acos(-1.0);
  for (double H : {1e-4, 5e-4, 1e-3}) {
    for (double T : {0.01, 0.06, 0.15, 0.3, 1.0}) {
      for (double t0 : {0.0, 0.05}) {
        const auto since = [t0](double t) { return t - t0; };
        const Signal ramp = [&](double t) {
          const double s = since(t);
          return s <= 0.0 ? 0.0 : s < T ? std::sin(pi * s / T) : 0.1 * std::exp(-(s - T) / 0.02);
        };
        const Signal pulse = [&](double t) {
          const double s = since(t);
          return s <= 0.0 || s >= T ? 0.0 : std::abs(std::sin(2.0 * pi * s / T));
        };
        EXPECT_FALSE(watch(ramp, kSmooth, H, 1.5)) << "ramp over " << T << " s, H = " << H;
        EXPECT_FALSE(watch(pulse, kSmooth, H, 1.5)) << "pulse of " << T << " s, H = " << H;
      }
    }
  }
}

TEST(GrowthWatch, CatchesAnUnstableModeGrowingFromRest) {
  // The same soil at rest under an unstable coupling: its error grows from rounding at one rate.
  for (double rho : {1.01, 1.04, 1.2}) {
    const double H = 1e-3;
    const auto seen = watch([&](double t) { return 1e-9 * std::pow(rho, t / H); }, kSmooth, H, 2.0);
    ASSERT_TRUE(seen.has_value()) << rho;
    EXPECT_NEAR(seen->first.per_step, rho, 0.1 * (rho - 1.0)) << rho;
  }
}

TEST(GrowthWatch, ADecayingMotionIsNeverGrowth) {
  const Signal decay = [](double t) { return 0.1 * std::exp(-5.0 * t); };
  EXPECT_FALSE(watch(decay, decay, 1e-3, 1.0));
}

}  // namespace
}  // namespace rumble
