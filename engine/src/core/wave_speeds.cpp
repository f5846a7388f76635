#include "core/wave_speeds.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace rumble {

WaveSpeeds wave_speeds(double E, double nu, double rho) {
  if (!(E > 0.0) || !(nu >= 0.0 && nu < 0.5) || !(rho > 0.0)) {
    std::ostringstream m;
    m << "wave speeds need E > 0 Pa, nu in [0, 0.5) and rho > 0 kg/m^3; got E = " << E
      << ", nu = " << nu << ", rho = " << rho;
    throw std::invalid_argument(m.str());
  }
  WaveSpeeds s;
  const double G = E / (2.0 * (1.0 + nu));
  s.shear = std::sqrt(G / rho);
  s.pressure = s.shear * std::sqrt(2.0 * (1.0 - nu) / (1.0 - 2.0 * nu));
  // Rayleigh equation in xi = c_R / c_s: (2 - xi^2)^2 = 4 sqrt(1 - xi^2) sqrt(1 - a^2 xi^2),
  // a = c_s / c_p. Its one non-trivial root lies in (0.87, 0.96) for nu in [0, 0.5): the
  // residual is negative at 0.8 and positive at 1 there; bisection to round-off.
  const double a2 = (s.shear / s.pressure) * (s.shear / s.pressure);
  const auto residual = [a2](double xi) {
    const double x2 = xi * xi;
    return (2.0 - x2) * (2.0 - x2) - 4.0 * std::sqrt(1.0 - x2) * std::sqrt(1.0 - a2 * x2);
  };
  double lo = 0.8, hi = 1.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (residual(mid) < 0.0 ? lo : hi) = mid;
  }
  s.rayleigh = 0.5 * (lo + hi) * s.shear;
  return s;
}

}  // namespace rumble
