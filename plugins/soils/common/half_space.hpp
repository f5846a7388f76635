// Closed-form impedance of a surface footing on a homogeneous elastic half-space, used to derive
// the reduced soils from soil properties (docs/soils.md, "Single footprint"). SI units: E [Pa],
// nu [-], rho [kg/m^3], lengths [m].
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

namespace rumble::soils {

struct SoilProperties {
  double E = 0.0;    // Young's modulus [Pa]
  double nu = 0.0;   // Poisson ratio [-]
  double rho = 0.0;  // density [kg/m^3]

  double shear_modulus() const { return E / (2.0 * (1.0 + nu)); }               // G [Pa]
  double shear_wave_speed() const { return std::sqrt(shear_modulus() / rho); }  // c_s [m/s]
};

/// Throws std::invalid_argument naming `where` (e.g. "winkler: params") unless E > 0,
/// 0 <= nu < 0.5 and rho > 0.
inline void check_properties(const SoilProperties& s, const std::string& where) {
  std::ostringstream m;
  if (!(s.E > 0.0) || !std::isfinite(s.E)) {
    m << where << "/E: Young's modulus must be > 0 Pa, got " << s.E;
  } else if (!(s.nu >= 0.0 && s.nu < 0.5)) {
    m << where << "/nu: Poisson ratio must be in [0, 0.5), got " << s.nu;
  } else if (!(s.rho > 0.0) || !std::isfinite(s.rho)) {
    m << where << "/rho: density must be > 0 kg/m^3, got " << s.rho;
  } else {
    return;
  }
  throw std::invalid_argument(m.str());
}

/// Gazetas (1991), rigid rectangle 2L x 2B (L >= B) on the half-space, static vertical
/// stiffness [N/m]: K_z = 2 G L / (1 - nu) (0.73 + 1.54 chi^0.75), chi = B / L.
inline double gazetas_vertical_stiffness(const SoilProperties& s, double length, double width) {
  const double L = 0.5 * std::max(length, width);
  const double B = 0.5 * std::min(length, width);
  return 2.0 * s.shear_modulus() * L / (1.0 - s.nu) * (0.73 + 1.54 * std::pow(B / L, 0.75));
}

/// Lysmer's analog (Gazetas 1991): radiation dashpot [N s/m] of a footing of area A [m^2],
/// C_z = rho V_La A with V_La = 3.4 c_s / (pi (1 - nu)) (its high-frequency limit).
inline double lysmer_dashpot(const SoilProperties& s, double area) {
  const double v_la = 3.4 * s.shear_wave_speed() / (std::numbers::pi * (1.0 - s.nu));
  return s.rho * v_la * area;
}

/// Wolf's cone, vertical (Wolf & Deeks 2004): soil mass [kg] trapped under a disc of radius
/// r0 = sqrt(A / pi) (same area), 2.4 (nu - 1/3) rho pi r0^3 for nu > 1/3, else 0.
inline double wolf_trapped_mass(const SoilProperties& s, double area) {
  if (s.nu <= 1.0 / 3.0) return 0.0;
  const double r0 = std::sqrt(area / std::numbers::pi);
  return 2.4 * (s.nu - 1.0 / 3.0) * s.rho * std::numbers::pi * r0 * r0 * r0;
}

/// Frequency-independent impedance of one rigid surface footing: K + i w C - w^2 m.
struct FootingImpedance {
  double stiffness = 0.0;  // K_z [N/m]
  double dashpot = 0.0;    // C_z [N s/m]
  double mass = 0.0;       // trapped mass [kg]
};

/// The three formulas above for a footprint length x width [m].
inline FootingImpedance surface_footing(const SoilProperties& s, double length, double width) {
  const double area = length * width;
  return {gazetas_vertical_stiffness(s, length, width), lysmer_dashpot(s, area),
          wolf_trapped_mass(s, area)};
}

}  // namespace rumble::soils
