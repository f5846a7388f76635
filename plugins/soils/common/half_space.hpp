// Elastic half-space formulas used to derive reduced soils from soil properties (docs/soils.md).
// All SI: E [Pa], nu [-], rho [kg/m^3], lengths [m].
#pragma once

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace rumble::soils {

struct SoilProperties {
  double E = 0.0, nu = 0.0, rho = 0.0;
  double shear_modulus() const { return E / (2.0 * (1.0 + nu)); }
  double shear_wave_speed() const { return std::sqrt(shear_modulus() / rho); }
};

inline void check_properties(const SoilProperties& s, const std::string& where) {
  if (!(s.E > 0.0))
    throw std::invalid_argument(where + "/E: must be > 0 Pa, got " + std::to_string(s.E));
  if (!(s.nu >= 0.0 && s.nu < 0.5))
    throw std::invalid_argument(where + "/nu: Poisson ratio must be in [0, 0.5), got " +
                                std::to_string(s.nu));
  if (!(s.rho > 0.0))
    throw std::invalid_argument(where + "/rho: must be > 0 kg/m^3, got " + std::to_string(s.rho));
}

/// Gazetas (1991): static vertical stiffness [N/m] of a rigid rectangle 2L x 2B (L >= B) on the
/// half-space: K = 2 G L / (1 - nu) (0.73 + 1.54 chi^0.75), chi = B / L.
inline double gazetas_vertical_stiffness(const SoilProperties& s, double length, double width) {
  const double L = 0.5 * std::max(length, width), B = 0.5 * std::min(length, width);
  return 2.0 * s.shear_modulus() * L / (1.0 - s.nu) * (0.73 + 1.54 * std::pow(B / L, 0.75));
}

/// Lysmer's analog: high-frequency radiation dashpot [N s/m] of a footprint of area A:
/// C = rho V_La A, V_La = 3.4 c_s / (pi (1 - nu)).
inline double lysmer_dashpot(const SoilProperties& s, double area) {
  const double v_la = 3.4 * s.shear_wave_speed() / (std::numbers::pi * (1.0 - s.nu));
  return s.rho * v_la * area;
}

/// Wolf's cone (Wolf & Deeks 2004): mass trapped under a disc of the same area, vertical
/// motion, non-zero only for nu > 1/3: 2.4 (nu - 1/3) rho pi r0^3 [kg].
inline double wolf_trapped_mass(const SoilProperties& s, double area) {
  if (s.nu <= 1.0 / 3.0) return 0.0;
  const double r0 = std::sqrt(area / std::numbers::pi);
  return 2.4 * (s.nu - 1.0 / 3.0) * s.rho * std::numbers::pi * r0 * r0 * r0;
}

/// Integral of 1/r over the rectangle [x1, x2] x [y1, y2] seen from the origin (Love 1929):
/// sum over the corners of +-(X ln(Y + R) + Y ln(X + R)), R = sqrt(X^2 + Y^2).
inline double inverse_distance_integral(double x1, double x2, double y1, double y2) {
  const auto F = [](double X, double Y) {
    const double R = std::hypot(X, Y);
    const double a = (X == 0.0 || Y + R <= 0.0) ? 0.0 : X * std::log(Y + R);
    const double b = (Y == 0.0 || X + R <= 0.0) ? 0.0 : Y * std::log(X + R);
    return a + b;
  };
  return F(x2, y2) - F(x1, y2) - F(x2, y1) + F(x1, y1);
}

/// Mean vertical surface displacement [m/N] over a target rectangle (centre (dx, 0), sides
/// length x width, the length across the track along y) per unit force spread uniformly on a
/// loaded rectangle of the same size centred at the origin: Boussinesq, u = (1 - nu^2) /
/// (pi E) * q * integral(1/r), averaged with 20 x 20 Gauss-Legendre points (converged to
/// 1e-4 on the square's known mean factor 0.946, even for the loaded rectangle itself).
inline double flexible_mean_compliance(const SoilProperties& s, double length, double width,
                                       double dx) {
  static constexpr std::array<double, 10> kNodes = {
      0.0765265211334973, 0.2277858511416451, 0.3737060887154195, 0.5108670019508271,
      0.6360536807265150, 0.7463319064601508, 0.8391169718222188, 0.9122344282513259,
      0.9639719272779138, 0.9931285991850949};
  static constexpr std::array<double, 10> kWeights = {
      0.1527533871307258, 0.1491729864726037, 0.1420961093183820, 0.1316886384491766,
      0.1181945319615184, 0.1019301198172404, 0.0832767415767048, 0.0626720483341091,
      0.0406014298003869, 0.0176140071391521};
  const double a = 0.5 * width, b = 0.5 * length;  // half sides: along x, along y
  double sum = 0.0;
  for (int i = 0; i < 20; ++i) {
    const double xi = (i < 10 ? -kNodes[9 - i] : kNodes[i - 10]);
    const double wi = (i < 10 ? kWeights[9 - i] : kWeights[i - 10]);
    for (int j = 0; j < 20; ++j) {
      const double eta = (j < 10 ? -kNodes[9 - j] : kNodes[j - 10]);
      const double wj = (j < 10 ? kWeights[9 - j] : kWeights[j - 10]);
      const double x = dx + a * xi, y = b * eta;
      sum += wi * wj * inverse_distance_integral(-a - x, a - x, -b - y, b - y);
    }
  }
  const double mean_integral = sum / 4.0;  // Gauss weights sum to 2 per direction
  const double area = 4.0 * a * b;
  return (1.0 - s.nu * s.nu) / (std::numbers::pi * s.E) * mean_integral / area;
}

}  // namespace rumble::soils
