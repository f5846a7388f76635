// Body and surface wave speeds of a homogeneous, isotropic, linear elastic soil
// (physics.md §4.1-4.2). The engine warns when a vehicle runs faster than the Rayleigh speed
// (critical-speed regime).
#pragma once

namespace rumble {

struct WaveSpeeds {
  double shear = 0.0;     // c_s = sqrt(G / rho), G = E / (2 (1 + nu)) [m/s]
  double pressure = 0.0;  // c_p = c_s sqrt(2 (1 - nu) / (1 - 2 nu)) [m/s]
  double rayleigh = 0.0;  // c_R = c_s rayleigh_speed_ratio(nu) [m/s]
};

/// c_R / c_s: the root in (0, 1) of the Rayleigh equation
///   (2 - xi^2)^2 = 4 sqrt(1 - xi^2) sqrt(1 - kappa xi^2),  kappa = c_s^2/c_p^2,
/// solved as the cubic in x = xi^2 that squaring it gives (Rayleigh 1885; the form physics.md §9
/// calls Kausel's cubic):
///   x^3 - 8 x^2 + (24 - 16 kappa) x - 16 (1 - kappa) = 0,
/// which has exactly one root in (0, 1) (the others, when real, exceed 1 and are spurious).
/// 0.8740 at nu = 0, 0.9194 at nu = 1/4, 0.9553 as nu -> 1/2.
/// Throws std::invalid_argument for nu outside [0, 0.5).
double rayleigh_speed_ratio(double nu);

/// E [Pa] > 0, nu in [0, 0.5), rho [kg/m^3] > 0; throws std::invalid_argument otherwise, with
/// the text "wave speeds: <what> must be ..., got <value>".
WaveSpeeds wave_speeds(double E, double nu, double rho);

inline double rayleigh_wave_speed(double E, double nu, double rho) {
  return wave_speeds(E, nu, rho).rayleigh;
}

}  // namespace rumble
