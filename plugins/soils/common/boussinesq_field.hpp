// Boussinesq's field: displacement and stress anywhere in an elastic half-space under a vertical
// point load on its surface (docs/fem-soil.md section 3.2; Johnson, Contact Mechanics, 1985,
// eq. 3.20-3.21). Frame of abi.h: x, y on the surface, z the depth (positive downward); the load
// P [N] pushes down (+z) at the origin. Tension positive. Written in Cartesian form so that the
// axis (r = 0) needs no special case; singular only at the load point.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <numbers>

namespace rumble::soils {

struct HalfSpacePoint {
  Eigen::Vector3d displacement;  // [m]
  Eigen::Matrix3d stress;        // [Pa], symmetric
};

/// The field at x (relative to the load point, x[2] >= 0, |x| > 0) of a load P [N] on a
/// half-space of shear modulus G [Pa] and Poisson's ratio nu.
inline HalfSpacePoint boussinesq_point_load(const Eigen::Vector3d& x, double P, double G,
                                            double nu) {
  const double X = x[0], Y = x[1], Z = x[2];
  const double R = x.norm(), R2 = R * R, R3 = R2 * R, R5 = R3 * R2, RZ = R + Z;
  const double c = 1.0 - 2.0 * nu;
  // Displacement: u_r = P/(4 pi G) [r Z / R^3 - c r / (R (R + Z))], u_z = P/(4 pi G)
  // [Z^2 / R^3 + 2 (1 - nu) / R]; u_r e_r = (x, y) times the bracket over r.
  const double U = P / (4.0 * std::numbers::pi * G);
  const double radial_over_r = U * (Z / R3 - c / (R * RZ));
  HalfSpacePoint out;
  out.displacement = {radial_over_r * X, radial_over_r * Y,
                      U * (Z * Z / R3 + 2.0 * (1.0 - nu) / R)};
  // Stress: sigma_theta on the horizontal plane, (sigma_r - sigma_theta) e_r e_r, with
  // (sigma_r - sigma_theta) / r^2 = A [c (2R + Z) / (R^3 (R + Z)^2) - 3 Z / R^5] regular on
  // the axis; tau_rz e_r = -3 A Z^2 / R^5 (x, y); sigma_z = -3 A Z^3 / R^5; A = P / (2 pi).
  const double A = P / (2.0 * std::numbers::pi);
  const double hoop = -A * c * (1.0 / (R * RZ) - Z / R3);
  const double radial_excess = A * (c * (2.0 * R + Z) / (R3 * RZ * RZ) - 3.0 * Z / R5);
  const double shear_over_r = -3.0 * A * Z * Z / R5;
  Eigen::Matrix3d& s = out.stress;
  s(0, 0) = hoop + radial_excess * X * X;
  s(1, 1) = hoop + radial_excess * Y * Y;
  s(0, 1) = s(1, 0) = radial_excess * X * Y;
  s(0, 2) = s(2, 0) = shear_over_r * X;
  s(1, 2) = s(2, 1) = shear_over_r * Y;
  s(2, 2) = -3.0 * A * Z * Z * Z / R5;
  return out;
}

}  // namespace rumble::soils
