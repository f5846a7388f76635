// Time stepping details: save/restore, sub-steps following the waveform, and the consistent
// start of massless footprints (Newmark with m = 0, i.e. the trapezoidal rule).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "soil_cases.hpp"
#include "soil_harness.hpp"

namespace rumble::test {
namespace {

const nlohmann::json kMassiveClm = {
    {"m_f", 400.0}, {"k_f", 1e8}, {"c_f", 1e5}, {"k_c", 5e7}, {"c_c", 5e4}};

/// Quadratic waveform coefficients over one macro step: F(tau) = a + b tau + c tau^2 per footprint.
VectorXd quadratic(Eigen::Index n, double step) {
  VectorXd coeff(3 * n);
  for (Eigen::Index i = 0; i < n; ++i) {
    coeff[i] = 1e5 * std::sin(0.7 * i + step);               // N
    coeff[n + i] = 2e4 * std::cos(1.1 * i - step);           // N per macro step
    coeff[2 * n + i] = -1e4 * std::sin(0.3 * i + 2 * step);  // N per macro step^2
  }
  return coeff;
}

TEST(SoilStepping, SaveRestoreRoundTripIsExact) {
  for (const char* type : {"clm", "winkler"}) {
    SCOPED_TRACE(type);
    const std::string params =
        std::string(type) == "clm" ? kMassiveClm.dump() : soil_params(kSoils[1]).dump();
    TestSoil a(type, params), b(type, params);
    a.accept_layout(sleeper_row(11));
    b.accept_layout(sleeper_row(11));
    a.initialize(VectorXd::Constant(11, 5e4));
    for (int k = 0; k < 20; ++k) a.advance(k * 1e-3, 1e-3, 2, quadratic(11, k));
    const std::vector<double> state = a.save();
    ASSERT_EQ(state.size(), 2u * 11u);  // u and v per footprint
    // Continue a; then replay the same steps on a restored a and on a fresh b.
    std::vector<VectorXd> first;
    for (int k = 20; k < 40; ++k) {
      a.advance(k * 1e-3, 1e-3, 2, quadratic(11, k));
      first.push_back(a.displacement());
      first.push_back(a.velocity());
    }
    for (TestSoil* s : {&a, &b}) {
      s->restore(state);
      for (int k = 20; k < 40; ++k) {
        s->advance(k * 1e-3, 1e-3, 2, quadratic(11, k));
        // Bitwise: the same operations on the same numbers.
        ASSERT_EQ(s->displacement(), first[2 * (k - 20)]);
        ASSERT_EQ(s->velocity(), first[2 * (k - 20) + 1]);
      }
    }
  }
}

TEST(SoilStepping, SubStepsEvaluateTheWaveform) {
  // One macro step of 8 sub-steps must equal 8 macro steps of one sub-step each, given the same
  // quadratic force re-parametrised on each eighth: the waveform is read at every sub-step.
  constexpr Eigen::Index n = 7;
  constexpr double H = 8e-4, h = 1e-4;  // s
  nlohmann::json params = kMassiveClm;
  params["max_step"] = h;
  TestSoil whole("clm", params.dump()), parts("clm", params.dump());
  whole.accept_layout(sleeper_row(n));
  parts.accept_layout(sleeper_row(n));
  const VectorXd c = quadratic(n, 0.3);
  const auto at = [&](double tau) {  // F(tau), tau in [0, 1] over H
    return VectorXd(c.segment(0, n) + tau * c.segment(n, n) + tau * tau * c.segment(2 * n, n));
  };
  whole.initialize(at(0.0));
  parts.initialize(at(0.0));
  whole.advance(0.0, H, 2, c);
  for (int s = 0; s < 8; ++s) {
    // F on [s/8, (s+1)/8] as a quadratic in its own sigma: a + b sigma + c sigma^2.
    const VectorXd f0 = at(s / 8.0), fm = at((s + 0.5) / 8.0), f1 = at((s + 1) / 8.0);
    VectorXd sub(3 * n);
    sub << f0, -3 * f0 + 4 * fm - f1, 2 * f0 - 4 * fm + 2 * f1;
    parts.advance(s * h, h, 2, sub);
  }
  // Only round-off differs (re-parametrised coefficients): 1e-12 of the motion.
  EXPECT_LT((whole.displacement() - parts.displacement()).norm(),
            1e-12 * parts.displacement().norm());
  EXPECT_LT((whole.velocity() - parts.velocity()).norm(), 1e-10 * parts.velocity().norm());
}

TEST(SoilStepping, MasslessFootprintFollowsAForceStepWithoutRinging) {
  // Winkler k, c, m = 0 under a force stepping from 0 to F at t = 0 (held, order 0):
  // u = F/k (1 - e^{-t/tau}), v = F/c e^{-t/tau}, tau = c/k = 1 ms. Started inconsistently
  // (v = 0), the trapezoidal rule would make v alternate in sign; the plugin starts from
  // C v = F - K u. The default sub-step (0.314 tau) cuts 1 ms into 4 steps of x = 0.25 tau: the
  // trapezoidal decay factor (1 - x/2)/(1 + x/2) differs from e^{-x} by 1.3e-3, so u errs by
  // at most ~0.2 % of F/k; tolerance 1 %.
  constexpr double k = 1e8, c = 1e5, F = 1e5, tau = c / k;
  TestSoil soil("winkler", nlohmann::json({{"k", k}, {"c", c}}).dump());
  soil.accept_layout(sleeper_row(1));
  soil.initialize(VectorXd::Zero(1));
  double previous_v = F / c;
  for (int step = 0; step < 20; ++step) {
    const double H = 1e-3, t = (step + 1) * H;
    soil.advance(step * H, H, 0, VectorXd::Constant(1, F));
    const double v = soil.velocity()[0];
    EXPECT_GT(v, 0.0);
    EXPECT_LT(v, previous_v);
    previous_v = v;
    EXPECT_NEAR(soil.displacement()[0], F / k * (1 - std::exp(-t / tau)), 1e-2 * F / k);
  }
}

TEST(SoilStepping, MasslessUndampedSpringIsQuasiStatic) {
  // m = c = 0: u = F/k at every instant and v = F'/k, exact for a quadratic force.
  constexpr Eigen::Index n = 5;
  nlohmann::json params = {{"k", 2e8}, {"c", 0.0}};
  params["max_step"] = 1e-4;
  TestSoil soil("winkler", params.dump());
  soil.accept_layout(sleeper_row(n));
  soil.initialize(VectorXd::Constant(n, 1e5));
  const double H = 1e-3;
  for (int step = 0; step < 5; ++step) {
    const VectorXd co = quadratic(n, step);
    soil.advance(step * H, H, 2, co);
    const VectorXd F1 = co.segment(0, n) + co.segment(n, n) + co.segment(2 * n, n);
    const VectorXd dF1 = (co.segment(n, n) + 2 * co.segment(2 * n, n)) / H;
    EXPECT_LT((soil.displacement() - F1 / 2e8).norm(), 1e-12 * (F1 / 2e8).norm());
    EXPECT_LT((soil.velocity() - dF1 / 2e8).norm(), 1e-9 * (dF1 / 2e8).norm());
  }
}

TEST(SoilStepping, MasslessClmMatchesTheExactStepResponse) {
  // The calibrated CLM has C = tau K (tau = C_z / K_z): under a held force step every footprint
  // follows u = K^-1 F (1 - e^{-t/tau}). Same tolerance argument as the Winkler step.
  const Soil& s = kSoils[1];
  TestSoil soil("clm", soil_params(s).dump());
  soil.accept_layout(sleeper_row(9));
  soil.initialize(VectorXd::Zero(9));
  VectorXd F = VectorXd::Zero(9);
  F[4] = 1e5;
  const VectorXd u_static = soil.receptance(0.0).real() * F;
  const std::complex<double> h0 = soil.receptance(0.0)(4, 4), h1 = soil.receptance(1.0)(4, 4);
  const double tau = std::tan(std::arg(h0 / h1)) / (2 * std::numbers::pi);  // H = G0/(1+i w tau)
  for (int step = 0; step < 10; ++step) {
    soil.advance(step * 1e-3, 1e-3, 0, F);
    const double t = (step + 1) * 1e-3;
    EXPECT_LT((soil.displacement() - u_static * (1 - std::exp(-t / tau))).norm(),
              1e-2 * u_static.norm());
  }
}

}  // namespace
}  // namespace rumble::test
