#include "track/hertz.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace rumble {
namespace {

[[noreturn]] void fail(const char* what, const char* rule, double value) {
  std::ostringstream m;
  m << "Hertz contact: " << what << ' ' << rule << ", got " << value;
  throw std::invalid_argument(m.str());
}

void check_inputs(double wheel_radius, double rail_radius, double E, double nu) {
  // Written as !(x > 0) so that NaN fails too; infinities are no radii either.
  if (!(wheel_radius > 0.0) || !std::isfinite(wheel_radius))
    fail("wheel radius", "must be > 0 m", wheel_radius);
  if (!(rail_radius > 0.0) || !std::isfinite(rail_radius))
    fail("rail radius", "must be > 0 m", rail_radius);
  if (!(E > 0.0) || !std::isfinite(E)) fail("Young's modulus E", "must be > 0 Pa", E);
  if (!(nu >= 0.0 && nu < 0.5)) fail("Poisson ratio nu", "must be in [0, 0.5)", nu);
}

void check_load(double hertz_constant, double load) {
  if (!(hertz_constant > 0.0)) fail("Hertz constant C_H", "must be > 0 N/m^1.5", hertz_constant);
  if (!(load >= 0.0)) fail("load P", "must be >= 0 N", load);
}

/// Complete elliptic integrals of the first and second kind, K and E, written through the two
/// sums that the Hertz formulas need without cancellation (Abramowitz & Stegun 17.6, the AGM):
///   K = pi / (2 a_N),  S = sum_{n>=0} 2^(n-1) c_n^2 = 1 - E/K,  so  K - E = K S,
///   T = e^2 - S = e^2/2 - sum_{n>=1} 2^(n-1) c_n^2,            so  E - K k'^2 = K T,
/// for modulus e and complementary modulus k' = sqrt(1 - e^2), both given so that neither is
/// recomputed from the other (k' near 0 and e near 0 both keep full relative precision).
struct EllipticSums {
  double K = 0.0, S = 0.0, T = 0.0;
};

EllipticSums elliptic_sums(double e, double k_prime) {
  // c_{n+1} = c_n^2 / (4 a_{n+1}) instead of (a_n - b_n)/2: no cancellation as a_n -> b_n.
  double a = 1.0, b = k_prime, c = e;
  double tail = 0.0, weight = 1.0;  // sum over n >= 1 of 2^(n-1) c_n^2, from n = 1
  for (int n = 0; n < 64; ++n) {    // quadratic convergence: < 10 steps for k' > 1e-300
    const double a_next = 0.5 * (a + b);
    const double b_next = std::sqrt(a * b);
    c = c * c / (4.0 * a_next);
    a = a_next;
    b = b_next;
    tail += weight * c * c;
    weight *= 2.0;
    if (c <= 1e-17 * a) break;  // the next term is below round-off of the sums
  }
  EllipticSums s;
  s.K = std::numbers::pi / (2.0 * a);
  s.S = 0.5 * e * e + tail;
  s.T = 0.5 * e * e - tail;
  return s;
}

/// B/A as a function of the ellipse's k' = b/a (Johnson §4.2, with the sums above):
///   B/A = (E/k'^2 - K) / (K - E) = T / (k'^2 S), decreasing from +inf (k' -> 0) to 1 (k' -> 1).
double curvature_ratio(double e, double k_prime) {
  const EllipticSums s = elliptic_sums(e, k_prime);
  return s.T / (k_prime * k_prime * s.S);
}

}  // namespace

HertzContact hertz_contact(double wheel_radius, double rail_radius, double E, double nu,
                           double load) {
  check_inputs(wheel_radius, rail_radius, E, nu);
  if (!(load >= 0.0) || !std::isfinite(load)) fail("load P", "must be >= 0 N", load);
  double A = 0.5 / wheel_radius, B = 0.5 / rail_radius;  // relative curvatures [1/m]
  if (B < A) std::swap(A, B);  // A: the smaller curvature, along the ellipse's major axis
  const double ratio = B / A;
  const double e_star = E / (2.0 * (1.0 - nu * nu));  // contact modulus of two equal bodies [Pa]
  HertzContact c;
  if (ratio - 1.0 <= 1e-10) {
    // Circular contact (Johnson §4.2) on the equivalent sphere R = 1/(2 sqrt(AB)); the elliptic
    // solution tends to it with a relative error of 0.02 (B/A - 1)^2 < 1e-21.
    const double R = 0.5 / std::sqrt(A * B);
    c.semi_major = c.semi_minor = std::cbrt(3.0 * load * R / (4.0 * e_star));
    c.approach = c.semi_major * c.semi_major / R;
    return c;
  }
  // Bisection on t = ln k' in [ln 1e-14, -1e-12]: monotone, bracketed, insensitive to how close
  // B/A is to 1 or how large it is (k' = 1e-14 covers B/A up to ~1e26). Near B/A = 1 the root is
  // ln k' ~ -(2/3)(B/A - 1) < -6.7e-11 for B/A - 1 > 1e-10, inside the bracket; t = 0 itself
  // (e = 0) would make B/A = 0/0.
  double lo = std::log(1e-14), hi = -1e-12;
  const auto ratio_at = [](double t) {
    const double k_prime = std::exp(t);
    return curvature_ratio(std::sqrt(-std::expm1(2.0 * t)), k_prime);
  };
  if (ratio_at(lo) < ratio) {
    std::ostringstream m;
    m << "Hertz contact: the radii " << wheel_radius << " m and " << rail_radius
      << " m are too different for an elliptic contact (curvature ratio " << ratio << ")";
    throw std::invalid_argument(m.str());
  }
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;  // interval at round-off
    (ratio_at(mid) > ratio ? lo : hi) = mid;
  }
  const double t = 0.5 * (lo + hi);
  const double k_prime = std::exp(t);
  const double e = std::sqrt(-std::expm1(2.0 * t));
  const EllipticSums s = elliptic_sums(e, k_prime);
  // Johnson §4.2 with p0 = 3P/(2 pi a b): a^3 = 3 P (K - E) / (2 pi e^2 E* A),
  // delta = 3 P K / (2 pi a E*); (K - E)/e^2 = K S / e^2 with S / e^2 -> 1/2 for e -> 0.
  c.eccentricity = e;
  c.semi_major =
      std::cbrt(3.0 * load * s.K * (s.S / (e * e)) / (2.0 * std::numbers::pi * e_star * A));
  c.semi_minor = c.semi_major * k_prime;
  c.approach = c.semi_major > 0.0
                   ? 3.0 * load * s.K / (2.0 * std::numbers::pi * c.semi_major * e_star)
                   : 0.0;
  return c;
}

double hertz_constant(double wheel_radius, double rail_radius, double E, double nu) {
  const double P = 1.0;  // N; C_H does not depend on the load (delta ~ P^(2/3))
  const HertzContact c = hertz_contact(wheel_radius, rail_radius, E, nu, P);
  return P / (c.approach * std::sqrt(c.approach));
}

double hertz_constant_approx(double wheel_radius, double rail_radius, double E, double nu) {
  check_inputs(wheel_radius, rail_radius, E, nu);
  return 2.0 * E / (3.0 * (1.0 - nu * nu)) * std::sqrt(std::sqrt(wheel_radius * rail_radius));
}

double static_approach(double hertz_constant, double load) {
  check_load(hertz_constant, load);
  return std::cbrt(load / hertz_constant) * std::cbrt(load / hertz_constant);
}

double linearized_stiffness(double hertz_constant, double load) {
  check_load(hertz_constant, load);
  return 1.5 * std::cbrt(hertz_constant * hertz_constant) * std::cbrt(load);
}

}  // namespace rumble
