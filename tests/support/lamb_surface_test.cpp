// Lamb's problem surface response (lamb_surface.hpp) against docs/physics.md §4 (Kausel's table for
// nu = 0.25, 0.30, 1/3, the Pekeris nu = 1/4 form, the dimensional example) and §2 (c_R/c_s);
// the ramped-load response against its definition, integrated here by quadrature.
#include "lamb_surface.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "expect_message.hpp"

namespace rumble::test {
namespace {

double plateau(double nu) {
  return (1.0 - nu) / (2.0 * std::numbers::pi);
}
double tau_p(double nu) {
  return std::sqrt((1.0 - 2.0 * nu) / (2.0 - 2.0 * nu));
}
double tau_r(double nu) {
  return 1.0 / rayleigh_speed_ratio(nu);
}

// docs/physics.md §4 reference values of U = u_z G r / P, printed to five decimals.
struct TableRow {
  double tau;
  double u[3];  // nu = 0.25, 0.30, 1/3
};
constexpr double kTableNu[3] = {0.25, 0.30, 1.0 / 3.0};
constexpr TableRow kTable[] = {
    {0.60, {-0.00603, -0.00879, -0.01047}}, {0.70, {-0.00305, -0.00461, -0.00586}},
    {0.80, {-0.00326, -0.00438, -0.00533}}, {0.90, {-0.00907, -0.00974, -0.01037}},
    {0.95, {-0.01586, -0.01641, -0.01694}}, {1.00, {-0.02913, -0.03017, -0.03104}},
    {1.02, {-0.04885, -0.05190, -0.05435}}, {1.05, {-0.10451, -0.12139, -0.13770}},
};

TEST(LambSurface, MatchesKauselTable) {
  // Five decimals: rounding alone is 5e-6; 2e-5 also covers the table's own "two codes agree to
  // 5 digits". nu = 0.30 and 1/3 take the complex-conjugate-root branch, nu = 0.25 the real one.
  for (const TableRow& row : kTable) {
    for (int i = 0; i < 3; ++i) {
      SCOPED_TRACE(::testing::Message() << "tau " << row.tau << ", nu " << kTableNu[i]);
      EXPECT_NEAR(lamb_step_surface_u(row.tau, kTableNu[i]), row.u[i], 2e-5);
    }
  }
}

TEST(LambSurface, ArrivalTimesMatchTable) {
  // tau_P and tau_R rows, printed to four decimals.
  constexpr double kTauP[3] = {0.5774, 0.5345, 0.5000};
  constexpr double kTauR[3] = {1.0877, 1.0783, 1.0724};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(tau_p(kTableNu[i]), kTauP[i], 5e-5);
    EXPECT_NEAR(tau_r(kTableNu[i]), kTauR[i], 5e-5);
  }
}

TEST(LambSurface, StaticPlateauAfterRayleighWave) {
  constexpr double kTableStatic[3] = {0.11937, 0.11141, 0.10610};
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(plateau(kTableNu[i]), kTableStatic[i], 5e-6);
  for (double nu : {0.0, 0.1, 0.25, 0.3, 1.0 / 3.0, 0.45, 0.49}) {
    for (double tau : {1.001 * tau_r(nu), 1.5, 3.0, 100.0}) {
      EXPECT_DOUBLE_EQ(lamb_step_surface_u(tau, nu), plateau(nu)) << "nu " << nu;
    }
  }
  EXPECT_DOUBLE_EQ(lamb_step_surface_u(2.0, 0.25), 3.0 / (8.0 * std::numbers::pi));  // Pekeris
}

TEST(LambSurface, ZeroBeforePArrivalAndContinuousAtIt) {
  for (double nu : {0.0, 0.25, 0.3, 1.0 / 3.0, 0.45}) {
    const double a = tau_p(nu);
    for (double tau : {-1.0, 0.0, 0.3 * a, 0.999 * a}) EXPECT_EQ(lamb_step_surface_u(tau, nu), 0.0);
    // The displacement starts from zero at the P arrival (no jump).
    EXPECT_NEAR(lamb_step_surface_u(a + 1e-9, nu), 0.0, 1e-8) << "nu " << nu;
  }
}

TEST(LambSurface, ContinuousAtSArrivalAndSingularAtRayleigh) {
  for (double nu : {0.0, 0.2, 0.25, 0.3, 1.0 / 3.0, 0.4, 0.49}) {
    SCOPED_TRACE(::testing::Message() << "nu " << nu);
    // The two closed-form windows meet at tau = 1.
    EXPECT_NEAR(lamb_step_surface_u(1.0 - 1e-12, nu), lamb_step_surface_u(1.0 + 1e-12, nu), 1e-9);
    // -> -infinity (1/sqrt) just before tau_R, opposite to the load.
    const double tr = tau_r(nu);
    EXPECT_LT(lamb_step_surface_u(tr * (1.0 - 1e-10), nu), -1e3 * plateau(nu));
    EXPECT_EQ(lamb_step_surface_u(lamb_detail::constants(nu).tau_r, nu),
              -std::numeric_limits<double>::infinity());
  }
}

TEST(LambSurface, ContinuousInNuThroughComplexRoots) {
  // Below nu* = 0.26308206... the two spurious roots are real, above they are complex
  // conjugates, at nu* a double root where A1 and A2 blow up and cancel: the response must not
  // notice. Against the mean of nu* -+ 1e-5; |dU/dnu| < 0.5 here, so the offsets move U < 5e-7.
  constexpr double kNuStar = 0.2630820649;
  for (double tau : {0.6, 0.7, 0.8, 0.9, 0.95, 1.0, 1.02, 1.05}) {
    const double mean =
        0.5 * (lamb_step_surface_u(tau, kNuStar - 1e-5) + lamb_step_surface_u(tau, kNuStar + 1e-5));
    for (double offset : {-1e-6, -1e-12, 0.0, 1e-12, 1e-6}) {
      EXPECT_NEAR(lamb_step_surface_u(tau, kNuStar + offset), mean, 1e-6)
          << "tau " << tau << ", nu* + " << offset;
    }
  }
}

TEST(LambSurface, RayleighRatioMatchesTable) {
  // docs/physics.md §2, printed to four decimals.
  struct Row {
    double nu, ratio;
  };
  constexpr Row kRatios[] = {{0.0, 0.8740}, {0.2, 0.9110},       {0.25, 0.9194},
                             {0.3, 0.9274}, {1.0 / 3.0, 0.9325}, {0.35, 0.9350},
                             {0.4, 0.9422}, {0.45, 0.9490},      {0.49, 0.9541}};
  for (const Row& row : kRatios) EXPECT_NEAR(rayleigh_speed_ratio(row.nu), row.ratio, 1e-4);
  EXPECT_NEAR(rayleigh_speed_ratio(0.25), std::sqrt(4.0 / (3.0 + std::sqrt(3.0))), 1e-14);
}

// Pekeris (1955), nu = 1/4, docs/physics.md §4.
double pekeris_u(double tau) {
  const double s3 = std::sqrt(3.0), t2 = tau * tau;
  const double rayleigh = std::sqrt(3.0 * s3 + 5.0) / std::sqrt((3.0 + s3) / 4.0 - t2);
  if (tau < 1.0) {
    return (6.0 - s3 / std::sqrt(t2 - 0.25) +
            std::sqrt(3.0 * s3 - 5.0) / std::sqrt(t2 - (3.0 - s3) / 4.0) - rayleigh) /
           (32.0 * std::numbers::pi);
  }
  return (6.0 - rayleigh) / (16.0 * std::numbers::pi);
}

TEST(LambSurface, PekerisClosedFormAtQuarterPoisson) {
  const double a = 1.0 / std::sqrt(3.0), tr = tau_r(0.25);
  for (double tau :
       {a + 1e-6, 0.58, 0.6, 0.65, 0.75, 0.85, 0.99, 1.0, 1.01, 1.04, 1.08, tr - 1e-6}) {
    const double expected = pekeris_u(tau);
    EXPECT_NEAR(lamb_step_surface_u(tau, 0.25), expected, 1e-12 * (1.0 + std::abs(expected)))
        << "tau " << tau;
  }
}

// docs/physics.md §4 dimensional example: E = 155 MPa, nu = 0.3, rho = 1800, r = 5 m, P = 1 kN.
constexpr double kE = 155e6, kNu = 0.3, kRho = 1800.0, kR = 5.0, kP = 1000.0;
const double kG = kE / (2.0 * (1.0 + kNu));
const double kCs = std::sqrt(kG / kRho);

TEST(LambSurface, DimensionalExample) {
  EXPECT_NEAR(lamb_step_surface_displacement(1.0, kR, kP, kE, kNu, kRho), 3.74e-7, 5e-10);
  // Arrivals t_P = 14.7 ms, t_S = 27.5 ms, t_R = 29.6 ms (to 0.1 ms).
  EXPECT_NEAR(tau_p(kNu) * kR / kCs, 14.7e-3, 5e-5);
  EXPECT_NEAR(kR / kCs, 27.5e-3, 5e-5);
  EXPECT_NEAR(tau_r(kNu) * kR / kCs, 29.6e-3, 5e-5);
  EXPECT_EQ(lamb_step_surface_displacement(14.6e-3, kR, kP, kE, kNu, kRho), 0.0);
  for (double t : {16e-3, 25e-3, 28.5e-3, 40e-3}) {
    EXPECT_DOUBLE_EQ(lamb_step_surface_displacement(t, kR, kP, kE, kNu, kRho),
                     kP / (kG * kR) * lamb_step_surface_u(kCs * t / kR, kNu));
  }
}

TEST(LambSurface, RefusesBadInput) {
  expect_invalid_argument([] { lamb_step_surface_u(1.0, 0.5); }, "Lamb: nu must be in [0, 0.5)");
  expect_invalid_argument([] { rayleigh_speed_ratio(-0.1); }, "Lamb: nu must be in [0, 0.5)");
  expect_invalid_argument([] { lamb_step_surface_displacement(1.0, 0.0, kP, kE, kNu, kRho); },
                          "Lamb: r must be > 0 m");
  expect_invalid_argument(
      [] { lamb_ramped_surface_displacement(1.0, kR, kP, kE, kNu, kRho, -1.0); },
      "Lamb: t_ramp must be >= 0 s");
}

// The mean of U over [tau1, tau2] by 8-point Gauss-Legendre on 400 panels per smooth piece,
// split at tau_P, 1 and tau_R; on the piece ending at tau_R, tau = tau_R - s^2 turns the
// 1/sqrt(tau_R - tau) singularity into a smooth integrand. Independent of the closed-form
// antiderivative that lamb_ramped_surface_displacement uses.
double mean_u_by_quadrature(double tau1, double tau2, double nu) {
  static constexpr double kNodes[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                       0.9602898564975363};
  static constexpr double kWeights[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                         0.1012285362903763};
  const auto integrate = [](double lo, double hi, auto&& f) {
    constexpr int kPanels = 400;
    const double h = (hi - lo) / kPanels;
    double sum = 0.0;
    for (int p = 0; p < kPanels; ++p) {
      const double mid = lo + (p + 0.5) * h;
      for (int k = 0; k < 4; ++k) {
        sum += kWeights[k] * (f(mid - 0.5 * h * kNodes[k]) + f(mid + 0.5 * h * kNodes[k]));
      }
    }
    return 0.5 * h * sum;
  };
  const double tr = tau_r(nu);
  std::vector<double> cuts = {tau1};
  for (double b : {tau_p(nu), 1.0, tr}) {
    if (b > tau1 && b < tau2) cuts.push_back(b);
  }
  cuts.push_back(tau2);
  double total = 0.0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double lo = cuts[i], hi = cuts[i + 1];
    if (hi == tr) {
      total += integrate(0.0, std::sqrt(tr - lo),
                         [&](double s) { return lamb_step_surface_u(tr - s * s, nu) * 2.0 * s; });
    } else {
      total += integrate(lo, hi, [&](double tau) { return lamb_step_surface_u(tau, nu); });
    }
  }
  return total / (tau2 - tau1);
}

double ramped(double t, double t_ramp) {
  return lamb_ramped_surface_displacement(t, kR, kP, kE, kNu, kRho, t_ramp);
}
double step(double t) {
  return lamb_step_surface_displacement(t, kR, kP, kE, kNu, kRho);
}

TEST(LambSurfaceRamp, IsTheWindowMeanOfTheStepResponse) {
  // Windows straddling tau_P, tau_S, tau_R (singular), ending at tau_R, and both sides of it;
  // for nu = 0.25 (real roots) and 0.3, 1/3 (complex roots). 1e-9 of the static value: the
  // quadrature's accuracy, the closed form being exact to round-off.
  for (double nu : {0.25, 0.3, 1.0 / 3.0}) {
    const double tr = tau_r(nu), a = tau_p(nu);
    const double windows[][2] = {{a - 0.02, a + 0.03}, {0.7, 0.9}, {0.95, 1.03},   {1.0, tr},
                                 {1.03, tr + 0.01},    {0.5, 1.5}, {tr, tr + 0.05}};
    for (const auto& w : windows) {
      SCOPED_TRACE(::testing::Message() << "nu " << nu << ", window " << w[0] << ".." << w[1]);
      const double G = 1.0, r = 1.0, rho = 1.0, E = 2.0 * (1.0 + nu) * G;  // c_s = 1: t = tau
      const double mean = lamb_ramped_surface_displacement(w[1], r, 1.0, E, nu, rho, w[1] - w[0]);
      EXPECT_NEAR(mean, mean_u_by_quadrature(w[0], w[1], nu), 1e-9 * plateau(nu));
    }
  }
}

TEST(LambSurfaceRamp, EqualsStepResponseOnThePlateau) {
  const double t_r = tau_r(kNu) * kR / kCs;
  for (double t_ramp : {1e-3, 2e-3, 5e-3}) {
    for (double t : {t_r + t_ramp + 1e-4, t_r + t_ramp + 10e-3, 1.0}) {
      EXPECT_NEAR(ramped(t, t_ramp), step(t), 1e-3 * std::abs(step(t))) << t_ramp << " s, " << t;
    }
  }
}

TEST(LambSurfaceRamp, FiniteAndContinuousThroughRayleighArrival) {
  const double t_ramp = 1e-3, t_r = tau_r(kNu) * kR / kCs, u_static = step(1.0);
  // Finite on a fine scan across the whole response, the singular instants included.
  for (double t = 0.0; t < 40e-3; t += 1e-5) EXPECT_TRUE(std::isfinite(ramped(t, t_ramp))) << t;
  // At the two instants where the window has the singularity at an end, the mean is only
  // Hoelder-1/2 continuous: a jump over h shrinks like sqrt(h), by 10 for each factor 100 in h.
  for (double t_s : {t_r, t_r + t_ramp}) {
    ASSERT_TRUE(std::isfinite(ramped(t_s, t_ramp)));
    const auto jump = [&](double h) {
      return std::max(std::abs(ramped(t_s + h, t_ramp) - ramped(t_s, t_ramp)),
                      std::abs(ramped(t_s - h, t_ramp) - ramped(t_s, t_ramp)));
    };
    for (double h : {1e-7, 1e-9}) {
      const double ratio = jump(h / 100.0) / jump(h);
      EXPECT_GT(ratio, 0.05) << "t " << t_s << ", h " << h;
      EXPECT_LT(ratio, 0.2) << "t " << t_s << ", h " << h;
    }
    EXPECT_LT(jump(1e-11), 1e-3 * u_static);
  }
}

TEST(LambSurfaceRamp, TendsToStepResponseAsRampShrinks) {
  const double t_s = kR / kCs, u_static = step(1.0);
  // Away from the singularity: in the P-S window, the S-R window and on the plateau. The error
  // is ~U' t_ramp / 2 (first order) down to the round-off of the difference of antiderivatives
  // (~1e-16 tau / tau_ramp of the plateau: 1e-9 at t_ramp = 1e-8 s).
  for (double t : {0.8 * t_s, 0.95 * t_s, 1.03 * t_s, 1.5 * t_s}) {
    SCOPED_TRACE(::testing::Message() << "t " << t);
    double previous = std::numeric_limits<double>::infinity();
    for (double t_ramp : {1e-4, 1e-6, 1e-8}) {
      const double error = std::abs(ramped(t, t_ramp) - step(t));
      EXPECT_LE(error, previous + 1e-8 * u_static) << "t_ramp " << t_ramp;
      previous = error;
    }
    EXPECT_LT(previous, 1e-5 * std::abs(step(t)));
    EXPECT_EQ(ramped(t, 0.0), step(t));
  }
}

}  // namespace
}  // namespace rumble::test
