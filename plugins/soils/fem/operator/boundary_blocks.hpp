// The operator's blocks on the truncation surface: per node, the spring S and the dashpot D
// (3 x 3 each) that the absorbing boundary (boundary/absorbing_boundary.hpp) computes and every
// back end of the soil operator (soil_operator.hpp) applies. Lumped on the node: no extra unknowns,
// the explicit step stays explicit.
#pragma once

#include <Eigen/Core>
#include <cstdint>

namespace rumble::fem {

struct BoundaryNode {
  std::int32_t node = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();      // outward unit normal
  double area = 0.0;                                      // m^2
  double dashpot_normal = 0.0, dashpot_tangential = 0.0;  // N s/m
  Eigen::Matrix3d spring = Eigen::Matrix3d::Zero();       // N/m, symmetric positive definite

  /// y += B x for the block B = t I + (n - t) nn^T.
  static void apply(const Eigen::Vector3d& normal, double along_normal, double tangential,
                    const double* x, double* y) {
    const double xn = normal[0] * x[0] + normal[1] * x[1] + normal[2] * x[2];
    for (int c = 0; c < 3; ++c)
      y[c] += tangential * x[c] + (along_normal - tangential) * xn * normal[c];
  }
  /// y += scale D x, D the dashpots' block.
  void apply_dashpot(const double* x, double* y, double scale = 1.0) const {
    apply(normal, scale * dashpot_normal, scale * dashpot_tangential, x, y);
  }
  /// y += S x, S the spring.
  void apply_spring(const double* x, double* y) const {
    for (int r = 0; r < 3; ++r)
      y[r] += spring(r, 0) * x[0] + spring(r, 1) * x[1] + spring(r, 2) * x[2];
  }
};

}  // namespace rumble::fem
