#include "track/hertz.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace rumble {
namespace {

void check_inputs(double wheel_radius, double rail_radius, double E, double nu) {
  std::ostringstream m;
  if (!(wheel_radius > 0.0))
    m << "wheel radius must be > 0 m, got " << wheel_radius;
  else if (!(rail_radius > 0.0))
    m << "rail radius must be > 0 m, got " << rail_radius;
  else if (!(E > 0.0))
    m << "Young's modulus must be > 0 Pa, got " << E;
  else if (!(nu >= 0.0 && nu < 0.5))
    m << "Poisson ratio must be in [0, 0.5), got " << nu;
  else
    return;
  throw std::invalid_argument("Hertz contact: " + m.str());
}

/// Complete elliptic integrals K(k), E(k) of modulus k by the arithmetic-geometric mean
/// (quadratic convergence: 6 iterations reach round-off for k < 1 - 1e-12).
std::pair<double, double> elliptic_ke(double k) {
  double a = 1.0, b = std::sqrt(1.0 - k * k), c = k;
  double sum = 0.5 * c * c, power = 0.5;
  while (std::abs(c) > 1e-16) {
    const double a1 = 0.5 * (a + b);
    c = 0.5 * (a - b);
    b = std::sqrt(a * b);
    a = a1;
    power *= 2.0;
    sum += power * c * c;
  }
  const double K = std::numbers::pi / (2.0 * a);
  return {K, K * (1.0 - sum)};
}

}  // namespace

double hertz_constant(double wheel_radius, double rail_radius, double E, double nu) {
  check_inputs(wheel_radius, rail_radius, E, nu);
  double A = 0.5 / wheel_radius, B = 0.5 / rail_radius;  // relative curvatures [1/m]
  if (B < A) std::swap(A, B);  // A: the smaller curvature, along the ellipse's major axis
  const double ratio = B / A;
  const double e_star = E / (2.0 * (1.0 - nu * nu));  // contact modulus of two equal bodies
  if (ratio - 1.0 < 1e-12) {  // circular contact: a sphere of radius R = 1/(2A)
    const double R = 0.5 / A;
    return 4.0 / 3.0 * e_star * std::sqrt(R);
  }
  // B/A = (E/(1-e^2) - K) / (K - E) grows monotonically with the eccentricity e in (0, 1).
  const auto curvature_ratio = [](double e) {
    const auto [K, Ee] = elliptic_ke(e);
    return (Ee / (1.0 - e * e) - K) / (K - Ee);
  };
  double lo = 1e-6, hi = 1.0 - 1e-15;
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (curvature_ratio(mid) < ratio ? lo : hi) = mid;
  }
  const double e = 0.5 * (lo + hi);
  const auto [K, Ee] = elliptic_ke(e);
  const double P = 1.0;  // N; C_H does not depend on the load
  const double a = std::cbrt(3.0 * P * (K - Ee) / (2.0 * std::numbers::pi * e * e * e_star * A));
  const double delta = 3.0 * P * K / (2.0 * std::numbers::pi * a * e_star);
  return P / std::pow(delta, 1.5);
}

double hertz_constant_approx(double wheel_radius, double rail_radius, double E, double nu) {
  check_inputs(wheel_radius, rail_radius, E, nu);
  return 2.0 * E / (3.0 * (1.0 - nu * nu)) * std::sqrt(std::sqrt(wheel_radius * rail_radius));
}

double static_approach(double hertz_constant, double load) {
  return std::pow(load / hertz_constant, 2.0 / 3.0);
}

double linearized_stiffness(double hertz_constant, double load) {
  return 1.5 * std::pow(hertz_constant, 2.0 / 3.0) * std::cbrt(load);
}

}  // namespace rumble
