#include "core/wave_speeds.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace rumble {
namespace {

[[noreturn]] void fail(const char* what, const char* rule, double value) {
  std::ostringstream m;
  m << "wave speeds: " << what << ' ' << rule << ", got " << value;
  throw std::invalid_argument(m.str());
}

void check_nu(double nu) {
  if (!(nu >= 0.0 && nu < 0.5)) fail("Poisson ratio nu", "must be in [0, 0.5)", nu);
}

}  // namespace

double rayleigh_speed_ratio(double nu) {
  check_nu(nu);
  const double kappa = (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu));  // c_s^2 / c_p^2, in (0, 1/2]
  const auto cubic = [kappa](double x) {
    return ((x - 8.0) * x + (24.0 - 16.0 * kappa)) * x - 16.0 * (1.0 - kappa);
  };
  // cubic(0) = -16 (1 - kappa) < 0 and cubic(1) = 1 > 0: bisection keeps the bracket on the
  // physical root whatever the other two roots do; 200 halvings reach the last bit.
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (cubic(mid) < 0.0 ? lo : hi) = mid;
  }
  return std::sqrt(0.5 * (lo + hi));
}

WaveSpeeds wave_speeds(double E, double nu, double rho) {
  if (!(E > 0.0) || !std::isfinite(E)) fail("Young's modulus E", "must be > 0 Pa", E);
  check_nu(nu);
  if (!(rho > 0.0) || !std::isfinite(rho)) fail("density rho", "must be > 0 kg/m^3", rho);
  WaveSpeeds s;
  const double G = E / (2.0 * (1.0 + nu));  // shear modulus [Pa]
  s.shear = std::sqrt(G / rho);
  s.pressure = s.shear * std::sqrt(2.0 * (1.0 - nu) / (1.0 - 2.0 * nu));
  s.rayleigh = s.shear * rayleigh_speed_ratio(nu);
  return s;
}

}  // namespace rumble
