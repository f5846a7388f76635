// Time stepping against the exact frequency response: a harmonic force on the middle footprint,
// run until the transient has decayed, gives the steady amplitude and phase of H(f) F.
//
// Why the tolerances hold: Newmark's average acceleration is the trapezoidal rule on (u, v),
// i.e. Tustin's map s = (2/h)(z - 1)/(z + 1). Driven by the force sampled at the step ends, its
// steady state is exactly the continuous one at the warped frequency w_d = (2/h) tan(w h / 2),
// w_d / w - 1 = (w h)^2 / 12 + O((w h)^4): Newmark's period error. So
//  (1) against H(f_d) the response agrees to round-off and the residue of the transient, and
//  (2) against H(f) it differs by the change of H over that shift, kappa (w h)^2 / 12, with
//      kappa = |d ln H / d ln f| measured on the plugin's own FRF.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "soil_cases.hpp"
#include "soil_harness.hpp"

namespace rumble::test {
namespace {

using cd = std::complex<double>;

struct Model {
  const char* label;
  const char* type;
  nlohmann::json params;
  bool coupled;  // the neighbour moves too
};

// A massive, damped chain (modes 80-140 Hz, modal damping >= 25 %), the massless CLM calibrated
// on the medium soil (first order: C u' + K u = F), and a Winkler soil with Wolf's trapped mass
// (nu = 0.4: 90 kg per footprint, overdamped).
Model massive_clm() {
  return {"massive clm",
          "clm",
          {{"m_f", 400.0}, {"k_f", 1e8}, {"c_f", 1e5}, {"k_c", 5e7}, {"c_c", 5e4}},
          true};
}
Model massless_clm() {
  return {"medium-soil clm", "clm", soil_params(kSoils[1]), true};
}
Model winkler_trapped_mass() {
  return {"winkler nu = 0.4", "winkler", {{"E", 155e6}, {"nu", 0.4}, {"rho", 1800.0}}, false};
}

struct Steady {
  cd measured;          // complex amplitude of u at the footprint, per unit force [m/N]
  cd exact;             // H(f)
  cd warped;            // H(f_d)
  double kappa;         // |d ln H / d ln f| at f
  double period_error;  // (w h)^2 / 12
};

/// Drives footprint `centre` of 9 with F(t) = cos(w t) [N], samples per period, and measures the
/// complex amplitude of footprint `at` over the last period after `settle` seconds.
Steady run(const Model& model, double f, Eigen::Index at) {
  constexpr int kSamplesPerPeriod = 400;
  constexpr double kSettle = 0.3;  // s: every transient below 1e-11 (slowest rate 125 1/s)
  constexpr Eigen::Index kN = 9, kCentre = 4;
  const double h = 1.0 / (f * kSamplesPerPeriod), w = 2.0 * std::numbers::pi * f;
  nlohmann::json params = model.params;
  params["max_step"] = h;  // one Newmark step per macro step: F sampled at the step ends
  TestSoil soil(model.type, params.dump());
  soil.accept_layout(sleeper_row(kN));
  soil.initialize(VectorXd::Zero(kN));

  const auto force = [&](long k) {
    VectorXd F = VectorXd::Zero(kN);
    F[kCentre] = std::cos(w * static_cast<double>(k) * h);
    return F;
  };
  const long settle_steps =
      std::lround(std::ceil(kSettle / h / kSamplesPerPeriod)) * kSamplesPerPeriod;
  cd sum = 0.0;
  for (long k = 0; k < settle_steps + kSamplesPerPeriod; ++k) {
    soil.advance_linear(static_cast<double>(k) * h, h, force(k), force(k + 1));
    if (k + 1 > settle_steps) {
      // Over a whole period, (2/N) sum u_k e^{-i w t_k} is exactly the complex amplitude.
      sum += soil.displacement()[at] * std::exp(cd(0.0, -w * static_cast<double>(k + 1) * h));
    }
  }
  const double f_d = std::tan(w * h / 2.0) / (std::numbers::pi * h);
  constexpr double kDelta = 1e-4;
  const cd exact = soil.receptance(f)(at, kCentre);
  return {2.0 * sum / static_cast<double>(kSamplesPerPeriod), exact,
          soil.receptance(f_d)(at, kCentre),
          std::abs(soil.receptance(f * (1.0 + kDelta))(at, kCentre) - exact) /
              (kDelta * std::abs(exact)),
          (w * h) * (w * h) / 12.0};
}

void expect_steady_state_matches_frf(const Model& model) {
  for (const double f : {5.0, 20.0, 60.0}) {
    for (const Eigen::Index at : {Eigen::Index{4}, Eigen::Index{5}}) {  // driving point, neighbour
      if (at == 5 && !model.coupled) continue;
      SCOPED_TRACE(std::string(model.label) + " at " + std::to_string(f) + " Hz, footprint " +
                   std::to_string(at));
      const Steady s = run(model, f, at);
      // (1) Tustin equivalence: round-off of ~1e4 steps and the 1e-11 transient residue.
      EXPECT_LT(std::abs(s.measured - s.warped), 1e-8 * std::abs(s.warped));
      // (2) The period error: first order in the shift, 1.5 for its second-order remainder.
      const double tolerance = 1.5 * s.kappa * s.period_error + 1e-9;
      EXPECT_NEAR(std::abs(s.measured) / std::abs(s.exact), 1.0, tolerance);
      EXPECT_NEAR(std::arg(s.measured / s.exact), 0.0, tolerance);  // rad
      // The check can fail: the tolerance is far below the response's own phase.
      EXPECT_GT(std::abs(std::arg(s.exact)), 10.0 * tolerance);
    }
  }
}

TEST(SoilHarmonicResponse, MassiveClmMatchesItsFrequencyResponse) {
  expect_steady_state_matches_frf(massive_clm());
}

TEST(SoilHarmonicResponse, MasslessClmMatchesItsFrequencyResponse) {
  expect_steady_state_matches_frf(massless_clm());
}

TEST(SoilHarmonicResponse, WinklerWithTrappedMassMatchesItsFrequencyResponse) {
  expect_steady_state_matches_frf(winkler_trapped_mass());
}

}  // namespace
}  // namespace rumble::test
