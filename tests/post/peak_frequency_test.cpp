// The dominant frequency as the peak's half cycle (post/peak_frequency.hpp): exact for a sine
// at any phase, the burst's own frequency under a slow swell, and the same whether the record
// ends at 0.45 s or 0.5 s (the spectrum's largest bin, the definition before, moved from 39 Hz
// to 2 Hz between such records of the quick study: issue #29).
#include "post/peak_frequency.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "post/ppv.hpp"

namespace rumble::post {
namespace {

constexpr double kDt = 1e-3;  // s, the paper's macro step

std::vector<double> sampled(double t_end, double (*v)(double)) {
  std::vector<double> x;
  for (double t = 0.0; t < t_end - 0.5 * kDt; t += kDt) x.push_back(v(t));
  return x;
}

double peak_frequency(const std::vector<double>& x) {
  return peak_half_cycle_frequency(x, peak_abs(x).index, kDt);
}

TEST(PeakHalfCycleFrequency, IsASinesFrequencyAtAnyPhase) {
  for (double phase = 0.0; phase < 3.0; phase += 0.37) {
    std::vector<double> x;
    for (int k = 0; k < 500; ++k)
      x.push_back(std::sin(2.0 * std::numbers::pi * 39.0 * k * kDt + phase));
    EXPECT_NEAR(peak_frequency(x), 39.0, 0.2) << phase;  // linear crossings at 26 samples a cycle
  }
}

// A wheel's blow at a dip: a 39 Hz burst (10 mm/s, 25 ms wide) at 0.3 s over the load's slow
// swell (1.5 mm/s, 1.1 Hz), as a receiver near the track records it. The swell shifts the
// crossings of the burst's half cycles: the zero-crossing frequency is that of the velocity as
// recorded (36 Hz here).
double blow_on_swell(double t) {
  const double s = (t - 0.3) / 0.025;
  return 0.01 * std::exp(-0.5 * s * s) * std::sin(2.0 * std::numbers::pi * 39.0 * (t - 0.3) + 1.2) +
         0.0015 * std::sin(2.0 * std::numbers::pi * 1.1 * t);
}

TEST(PeakHalfCycleFrequency, BelongsToTheEventNotToTheRecordsLength) {
  const std::vector<double> whole = sampled(0.5, blow_on_swell),
                            shorter = sampled(0.45, blow_on_swell);
  // The half cycle of the continuous signal, found on a 1 us grid from the sampled peak.
  const double t_peak = static_cast<double>(peak_abs(whole).index) * kDt;
  const bool up = blow_on_swell(t_peak) > 0.0;
  double t0 = t_peak, t1 = t_peak;
  while ((blow_on_swell(t0) > 0.0) == up) t0 -= 1e-6;
  while ((blow_on_swell(t1) > 0.0) == up) t1 += 1e-6;
  EXPECT_NEAR(peak_frequency(whole), 0.5 / (t1 - t0), 0.01 * 0.5 / (t1 - t0));
  EXPECT_NEAR(0.5 / (t1 - t0), 36.0, 1.0);  // Hz: the swell stretches the burst's half cycle
  EXPECT_EQ(peak_frequency(whole), peak_frequency(shorter));
}

TEST(PeakHalfCycleFrequency, AHalfCycleOpenAtTheRecordsEndIsAQuarterPeriodFromThePeak) {
  // A 10 Hz cosine from its peak at t = 0: a quarter period (25 ms) to its first zero.
  std::vector<double> x;
  for (int k = 0; k < 40; ++k) x.push_back(std::cos(2.0 * std::numbers::pi * 10.0 * k * kDt));
  EXPECT_NEAR(peak_half_cycle_frequency(x, 0, kDt), 10.0, 0.05);
  // No crossing at all, a silent record, a peak out of range: no frequency.
  EXPECT_TRUE(std::isnan(peak_half_cycle_frequency(std::vector<double>(10, 1.0), 3, kDt)));
  EXPECT_TRUE(std::isnan(peak_half_cycle_frequency(std::vector<double>(10, 0.0), 3, kDt)));
  EXPECT_TRUE(std::isnan(peak_half_cycle_frequency(x, 99, kDt)));
}

}  // namespace
}  // namespace rumble::post
