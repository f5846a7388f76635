// Body and surface wave speeds of a homogeneous, isotropic, linear elastic soil
// (docs/physics.md §2), and the slowest of a layered profile. A soil that knows them reports
// them through the boundary (ABI 1.1 wave_speeds): the engine warns when a vehicle runs faster
// than the slowest Rayleigh speed (critical-speed regime) without reading the soil's params.
#pragma once

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "layered_soil.hpp"

namespace rumble::soils {

struct WaveSpeeds {
  double shear = 0.0;     // c_s = sqrt(G / rho), G = E / (2 (1 + nu)) [m/s]
  double pressure = 0.0;  // c_p = c_s sqrt(2 (1 - nu) / (1 - 2 nu)) [m/s]
  double rayleigh = 0.0;  // c_R = c_s rayleigh_speed_ratio(nu) [m/s]
};

namespace detail {

[[noreturn]] inline void wave_speed_failure(const char* what, const char* rule, double value) {
  std::ostringstream m;
  m << "wave speeds: " << what << ' ' << rule << ", got " << value;
  throw std::invalid_argument(m.str());
}

inline void check_poisson_ratio(double nu) {
  if (!(nu >= 0.0 && nu < 0.5)) wave_speed_failure("Poisson ratio nu", "must be in [0, 0.5)", nu);
}

}  // namespace detail

/// c_R / c_s: the root in (0, 1) of the Rayleigh equation
///   (2 - xi^2)^2 = 4 sqrt(1 - xi^2) sqrt(1 - kappa xi^2),  kappa = c_s^2/c_p^2,
/// solved as the cubic in x = xi^2 that squaring it gives (Rayleigh 1885; Kausel's Lamb solution
/// uses the equivalent cubic in 1 / x, docs/physics.md §2 and §4):
///   x^3 - 8 x^2 + (24 - 16 kappa) x - 16 (1 - kappa) = 0,
/// which has exactly one root in (0, 1) (the others, when real, exceed 1 and are spurious).
/// 0.8740 at nu = 0, 0.9194 at nu = 1/4, 0.9553 as nu -> 1/2.
/// Throws std::invalid_argument for nu outside [0, 0.5).
inline double rayleigh_speed_ratio(double nu) {
  detail::check_poisson_ratio(nu);
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

/// E [Pa] > 0, nu in [0, 0.5), rho [kg/m^3] > 0; throws std::invalid_argument otherwise, with
/// the text "wave speeds: <what> must be ..., got <value>".
inline WaveSpeeds wave_speeds(double E, double nu, double rho) {
  if (!(E > 0.0) || !std::isfinite(E))
    detail::wave_speed_failure("Young's modulus E", "must be > 0 Pa", E);
  detail::check_poisson_ratio(nu);
  if (!(rho > 0.0) || !std::isfinite(rho))
    detail::wave_speed_failure("density rho", "must be > 0 kg/m^3", rho);
  WaveSpeeds s;
  const double G = E / (2.0 * (1.0 + nu));  // shear modulus [Pa]
  s.shear = std::sqrt(G / rho);
  s.pressure = s.shear * std::sqrt(2.0 * (1.0 - nu) / (1.0 - 2.0 * nu));
  s.rayleigh = s.shear * rayleigh_speed_ratio(nu);
  return s;
}

inline double rayleigh_wave_speed(double E, double nu, double rho) {
  return wave_speeds(E, nu, rho).rayleigh;
}

/// The slowest shear, pressure and Rayleigh speeds of any layer and of the half-space below
/// them: a soft top layer governs the critical speed even over a stiff half-space.
inline WaveSpeeds slowest_wave_speeds(const std::vector<SoilLayer>& layers,
                                      const SoilProperties& half_space) {
  WaveSpeeds slowest = wave_speeds(half_space.E, half_space.nu, half_space.rho);
  for (const SoilLayer& l : layers) {
    const WaveSpeeds s = wave_speeds(l.properties.E, l.properties.nu, l.properties.rho);
    slowest.shear = std::min(slowest.shear, s.shear);
    slowest.pressure = std::min(slowest.pressure, s.pressure);
    slowest.rayleigh = std::min(slowest.rayleigh, s.rayleigh);
  }
  return slowest;
}

}  // namespace rumble::soils
