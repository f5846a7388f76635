// Body and surface wave speeds of a homogeneous, isotropic elastic soil (physics.md §4.1-4.2).
#pragma once

namespace rumble {

struct WaveSpeeds {
  double shear = 0.0;     // c_s = sqrt(G / rho) [m/s]
  double pressure = 0.0;  // c_p = c_s sqrt(2 (1 - nu) / (1 - 2 nu)) [m/s]
  double rayleigh = 0.0;  // c_R, the root of the Rayleigh equation [m/s]
};

/// E [Pa] > 0, nu in [0, 0.5), rho [kg/m^3] > 0; throws std::invalid_argument otherwise.
WaveSpeeds wave_speeds(double E, double nu, double rho);

inline double rayleigh_wave_speed(double E, double nu, double rho) {
  return wave_speeds(E, nu, rho).rayleigh;
}

}  // namespace rumble
