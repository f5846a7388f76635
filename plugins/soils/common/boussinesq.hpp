// Surface displacement and vertical stress of an elastic half-space under a uniformly loaded
// flexible rectangle (Boussinesq's point-load solution integrated over the rectangle; Love 1929
// corner terms). Used for the CLM neighbour coupling (docs/soils.md, "Coupled lumped mass") and
// the layered-soil weights. The footprint is `length` across the track (y) by `width` along it
// (x), as in rumble_footprint. Lengths in m.
#pragma once

#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <numbers>

namespace rumble::soils {

/// Integral of 1/R over the rectangle [x1, x2] x [y1, y2] of the surface, R the distance to the
/// origin [m]: the sum over the corners of +-(X ln(Y + R) + Y ln(X + R)).
inline double inverse_distance_integral(double x1, double x2, double y1, double y2) {
  const auto corner = [](double X, double Y) {
    const double R = std::hypot(X, Y);
    const double a = (X == 0.0 || Y + R <= 0.0) ? 0.0 : X * std::log(Y + R);
    const double b = (Y == 0.0 || X + R <= 0.0) ? 0.0 : Y * std::log(X + R);
    return a + b;
  };
  return corner(x2, y2) - corner(x1, y2) - corner(x2, y1) + corner(x1, y1);
}

/// Mean over a target footprint centred at (dx, 0) of the integral of 1/R over a loaded
/// footprint of the same size centred at the origin, divided by the loaded area [1/m]. The mean
/// vertical displacement of the target per unit force on the loaded one is
/// (1 - nu^2) / (pi E) times this. 20 x 20 Gauss points: converged to 1e-5 even for the loaded
/// footprint itself (square: 0.946 pi / side, the known mean settlement factor 0.946).
inline double mean_flexible_influence(double length, double width, double dx) {
  const double a = 0.5 * width, b = 0.5 * length;  // half sides along x and y
  // 20 x 20 Gauss-Legendre points (Boost.Math: exact for polynomials up to degree 39).
  using Gauss = boost::math::quadrature::gauss<double, 20>;
  const auto along_y = [&](double x) {
    return Gauss::integrate(
        [&](double y) { return inverse_distance_integral(-a - x, a - x, -b - y, b - y); }, -b, b);
  };
  const double mean_integral = Gauss::integrate(along_y, dx - a, dx + a) / (4.0 * a * b);
  return mean_integral / (4.0 * a * b);
}

/// r = u1 / u0: mean displacement of the neighbour at `spacing` over that of the loaded
/// footprint itself, flexible uniform pressure. Depends on the geometry only (not on E, nu).
inline double neighbour_compliance_ratio(double length, double width, double spacing) {
  return mean_flexible_influence(length, width, spacing) /
         mean_flexible_influence(length, width, 0.0);
}

/// Vertical stress under the centre of the loaded footprint at depth z [m], per unit pressure
/// [-]: four corners of the Holl/Newmark formula, each
/// (1/2pi) [atan(m n / (z R3)) + m n z / R3 (1/R1^2 + 1/R2^2)], m, n the half sides.
inline double centre_vertical_stress(double length, double width, double z) {
  if (z <= 0.0) return 1.0;
  const double m = 0.5 * length, n = 0.5 * width;
  const double r1 = m * m + z * z, r2 = n * n + z * z, r3 = std::sqrt(m * m + n * n + z * z);
  return 4.0 / (2.0 * std::numbers::pi) *
         (std::atan(m * n / (z * r3)) + m * n * z / r3 * (1.0 / r1 + 1.0 / r2));
}

}  // namespace rumble::soils
