// Lamb's problem, surface response: a vertical step point load P H(t) on the surface of a
// homogeneous, isotropic, linear elastic half-space, vertical displacement at distance r on the
// surface. Kausel's closed form (docs/physics.md §4; E. Kausel, "Lamb's problem at its simplest",
// Proc. R. Soc. A 2012, and his Lamb_3D.m v3.3), written here from the formulas restated there.
// It is the independent reference for the 3D FEM soil tests, so it uses nothing of the engine
// or the plugins (not even plugins/soils/common/wave_speeds.hpp).
//
// Sign convention (Kausel's): load and displacement are positive in the same direction, so the
// late-time value is the static Boussinesq displacement u_z = (1 - nu) P / (2 pi G r) > 0.
//
// Normalised quantities: tau = c_s t / r (dimensionless time), U = u_z G r / P (dimensionless
// displacement), a^2 = (c_s/c_p)^2 = (1 - 2 nu) / (2 - 2 nu); the P, S and Rayleigh waves
// arrive at tau_P = a, tau_S = 1 and tau_R = sqrt(x3) = c_s/c_R.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace rumble::test {

namespace lamb_detail {

using cplx = std::complex<double>;

inline void check_poisson_ratio(double nu) {
  if (!(nu >= 0.0 && nu < 0.5)) throw std::invalid_argument("Lamb: nu must be in [0, 0.5)");
}

// Everything of the closed form that depends on nu only.
struct Constants {
  double a = 0.0;           // tau_P = c_s / c_p
  double x3 = 0.0;          // (c_s / c_R)^2, the real root > 1
  double tau_r = 0.0;       // sqrt(x3) = c_s / c_R
  double f = 0.0;           // static plateau (1 - nu) / (2 pi)
  double A3 = 0.0;          // Rayleigh-pole coefficient (real and > 0)
  std::array<cplx, 2> x{};  // the two other roots x1, x2: both real (nu below ~0.2631) or a
                            // complex-conjugate pair (above)
  std::array<cplx, 2> A{};  // their coefficients A1, A2 (conjugate when the roots are)
};

// Roots of Kausel's cubic  p(x) = -16 (1 - a^2) x^3 + 8 (3 - 2 a^2) x^2 - 8 x + 1  (x = (c_s/c)^2
// for the zeros c of the Rayleigh function) and the coefficients
//   A_k = (x_k - 1/2)^2 sqrt(a^2 - x_k) / prod_{j != k} (x_k - x_j),  sqrt(x3 - a^2) for k = 3.
inline Constants constants(double nu) {
  check_poisson_ratio(nu);
  Constants c;
  const double a2 = (1.0 - 2.0 * nu) / (2.0 - 2.0 * nu);
  c.a = std::sqrt(a2);
  c.f = (1.0 - nu) / (2.0 * std::numbers::pi);
  const auto p = [a2](double x) {
    return ((-16.0 * (1.0 - a2) * x + 8.0 * (3.0 - 2.0 * a2)) * x - 8.0) * x + 1.0;
  };
  // p(1) = 1 > 0 and p(2) = 64 a^2 - 47 < 0 for a^2 <= 1/2: x3 is bracketed in (1, 2) for every
  // nu, and bisection to the last bit cannot leave the physical root.
  double lo = 1.0, hi = 2.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (p(mid) > 0.0 ? lo : hi) = mid;
  }
  c.x3 = 0.5 * (lo + hi);
  c.tau_r = std::sqrt(c.x3);
  // x1, x2 from Vieta (sum and product of the three roots), then the quadratic with complex
  // arithmetic: this covers the real pair and the complex-conjugate pair alike.
  const double sum = (3.0 - 2.0 * a2) / (2.0 * (1.0 - a2)) - c.x3;
  const double product = 1.0 / (16.0 * (1.0 - a2) * c.x3);
  // At nu* = 0.26308206... the pair is a double root: A1 and A2 grow like 1/(x1 - x2) and cancel
  // in their sum, which is a smooth symmetric function of the pair. A discriminant within 1e-12
  // of zero is set to -1e-12 (x1 - x2 = 1e-6 i): that moves the product x1 x2 by 2.5e-13, and
  // the cancellation costs ~eps / 1e-6; measured, U stays within ~1e-10 of its neighbours in nu.
  double discriminant = sum * sum - 4.0 * product;
  if (std::abs(discriminant) < 1e-12) discriminant = -1e-12;
  const cplx root = std::sqrt(cplx(discriminant, 0.0));
  c.x = {0.5 * (sum - root), 0.5 * (sum + root)};
  const double r0 = c.x3 - 0.5;
  c.A3 = r0 * r0 * std::sqrt(c.x3 - a2) / ((c.x3 - c.x[0]) * (c.x3 - c.x[1])).real();
  for (std::size_t k = 0; k < 2; ++k) {
    const cplx xk = c.x[k], xj = c.x[1 - k];
    c.A[k] = (xk - 0.5) * (xk - 0.5) * std::sqrt(a2 - xk) / ((xk - xj) * (xk - c.x3));
  }
  return c;
}

// U(tau) for a given set of constants (see lamb_step_surface_u).
inline double step_u(double tau, const Constants& c) {
  if (tau <= c.a) return 0.0;
  if (tau >= c.tau_r) {
    return tau == c.tau_r ? -std::numeric_limits<double>::infinity() : c.f;
  }
  const double rayleigh = c.A3 / std::sqrt(c.x3 - tau * tau);
  if (tau >= 1.0) return c.f * (1.0 - rayleigh);
  // Between the P and S arrivals. The two branch-point terms are complex conjugates when the
  // roots are, so their sum (taken as the real part) is real; principal square roots are those
  // of Lamb_3D.m.
  cplx branch = 0.0;
  for (std::size_t k = 0; k < 2; ++k) branch += c.A[k] / std::sqrt(tau * tau - c.x[k]);
  return 0.5 * c.f * (1.0 - branch.real() - rayleigh);
}

// W(tau) = integral of U from 0 to tau, in closed form, from
//   d/dtau log(tau + sqrt(tau^2 - x)) = 1 / sqrt(tau^2 - x)   (x real < a^2, or complex),
//   d/dtau asin(tau / sqrt(x3))        = 1 / sqrt(x3 - tau^2).
// On a <= tau <= 1 the principal branches are continuous (tau^2 - x_k never crosses the negative
// real axis, and tau + sqrt(.) has a positive real part), so the differences are exact. The
// 1/sqrt singularity at tau_R integrates to the finite W(tau_R), so W is continuous everywhere
// and exact to round-off: no quadrature.
inline double step_w(double tau, const Constants& c) {
  if (tau <= c.a) return 0.0;
  const double sqrt_x3 = c.tau_r;
  const auto branch_log = [&c](double t) {
    cplx s = 0.0;
    for (std::size_t k = 0; k < 2; ++k) s += c.A[k] * std::log(t + std::sqrt(t * t - c.x[k]));
    return s.real();
  };
  const auto pole = [&](double t) { return c.A3 * std::asin(std::min(t / sqrt_x3, 1.0)); };
  const auto w_ps = [&](double t) {  // a <= t <= 1
    return 0.5 * c.f * ((t - c.a) - (branch_log(t) - branch_log(c.a)) - (pole(t) - pole(c.a)));
  };
  if (tau <= 1.0) return w_ps(tau);
  const auto w_sr = [&](double t) {  // 1 <= t <= tau_R
    return w_ps(1.0) + c.f * ((t - 1.0) - (pole(t) - pole(1.0)));
  };
  if (tau <= c.tau_r) return w_sr(tau);
  return w_sr(c.tau_r) + c.f * (tau - c.tau_r);
}

inline void check_material(double r, double E, double rho) {
  if (!(r > 0.0)) throw std::invalid_argument("Lamb: r must be > 0 m");
  if (!(E > 0.0)) throw std::invalid_argument("Lamb: E must be > 0 Pa");
  if (!(rho > 0.0)) throw std::invalid_argument("Lamb: rho must be > 0 kg/m^3");
}

}  // namespace lamb_detail

/// c_R / c_s = 1 / sqrt(x3), x3 the real root > 1 of Kausel's cubic. nu in [0, 0.5), else
/// std::invalid_argument. 0.8740 at nu = 0, sqrt(4 / (3 + sqrt 3)) = 0.9194 at nu = 1/4.
inline double rayleigh_speed_ratio(double nu) {
  return 1.0 / std::sqrt(lamb_detail::constants(nu).x3);
}

/// Normalised vertical surface displacement U = u_z G r / P of the step load at tau = c_s t / r:
///   tau <= tau_P = a       0
///   a < tau < 1            f/2 [1 - A1/sqrt(tau^2 - x1) - A2/sqrt(tau^2 - x2)
///                                 - A3/sqrt(x3 - tau^2)]
///   1 <= tau < tau_R       f [1 - A3/sqrt(x3 - tau^2)]     (-> -infinity at tau_R)
///   tau = tau_R            -infinity
///   tau > tau_R            f = (1 - nu) / (2 pi)           (static Boussinesq)
/// nu in [0, 0.5), else std::invalid_argument.
inline double lamb_step_surface_u(double tau, double nu) {
  return lamb_detail::step_u(tau, lamb_detail::constants(nu));
}

/// Vertical surface displacement u_z [m] (positive in the load direction) at time t [s] >= 0
/// after a step load P [N] switched on at t = 0, at distance r [m] > 0; E [Pa], rho [kg/m^3].
/// u_z = P U(c_s t / r) / (G r), G = E / (2 (1 + nu)), c_s = sqrt(G / rho).
inline double lamb_step_surface_displacement(double t, double r, double P, double E, double nu,
                                             double rho) {
  lamb_detail::check_material(r, E, rho);
  const double G = E / (2.0 * (1.0 + nu));
  const double c_s = std::sqrt(G / rho);
  return P / (G * r) * lamb_step_surface_u(c_s * t / r, nu);
}

/// As lamb_step_surface_displacement, for a load rising linearly from 0 at t = 0 to P at
/// t = t_ramp [s] and held: by superposition, the time average of the step response over
/// [t - t_ramp, t] (the step response being 0 for negative times). Computed exactly from the
/// closed-form antiderivative of U (lamb_detail::step_w), so the integrable 1/sqrt singularity
/// at tau_R needs no quadrature: the result is finite and continuous in t, accurate to
/// round-off relative to W (about 1e-16 tau / (c_s t_ramp / r) relative; 1e-9 even for
/// c_s t_ramp / r = 1e-7). t_ramp = 0 gives the step response; t_ramp < 0 is refused.
inline double lamb_ramped_surface_displacement(double t, double r, double P, double E, double nu,
                                               double rho, double t_ramp) {
  if (!(t_ramp >= 0.0)) throw std::invalid_argument("Lamb: t_ramp must be >= 0 s");
  if (t_ramp == 0.0) return lamb_step_surface_displacement(t, r, P, E, nu, rho);
  lamb_detail::check_material(r, E, rho);
  const lamb_detail::Constants c = lamb_detail::constants(nu);
  const double G = E / (2.0 * (1.0 + nu));
  const double c_s = std::sqrt(G / rho);
  const double tau = c_s * t / r, tau_ramp = c_s * t_ramp / r;
  const double mean_u =
      (lamb_detail::step_w(tau, c) - lamb_detail::step_w(tau - tau_ramp, c)) / tau_ramp;
  return P / (G * r) * mean_u;
}

}  // namespace rumble::test
