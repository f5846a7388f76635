#include "rigid_rail.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace rumble::test {

Equilibrium rigid_rail_statics(TestVehicle& v) {
  const Eigen::Index n = v.dofs();
  const Eigen::Index nw = v.wheel_count();
  Equilibrium e;
  e.q = VectorXd::Zero(n);
  e.contact_force = VectorXd::Zero(nw);
  const VectorXd zero = VectorXd::Zero(n);
  const double weight_scale = v.forces(zero, zero).cwiseAbs().sum() + 1.0;  // N
  VectorXd z;
  MatrixXd j, k, c;
  for (e.iterations = 0; e.iterations < 50; ++e.iterations) {
    v.wheel_kinematics(e.q, z, j);
    const VectorXd r = v.forces(e.q, zero) - j.transpose() * e.contact_force;
    if (r.norm() < 1e-12 * weight_scale && z.norm() < 1e-13) return e;
    v.tangent(e.q, zero, k, c);
    // [K  J^T] [dq]   [ r ]     from r - K dq - J^T dF = 0 and z + J dq = 0.
    // [J  0  ] [dF] = [-z ]
    MatrixXd a = MatrixXd::Zero(n + nw, n + nw);
    a.topLeftCorner(n, n) = k;
    a.topRightCorner(n, nw) = j.transpose();
    a.bottomLeftCorner(nw, n) = j;
    VectorXd b(n + nw);
    b << r, -z;
    const VectorXd step = a.fullPivLu().solve(b);
    e.q += step.head(n);
    e.contact_force += step.tail(nw);
  }
  throw std::runtime_error("rigid-rail statics did not converge in 50 Newton iterations");
}

VectorXd rigid_rail_frequencies_hz(TestVehicle& v, const VectorXd& q) {
  const Eigen::Index n = v.dofs();
  VectorXd z;
  MatrixXd j, k, c;
  v.wheel_kinematics(q, z, j);
  v.tangent(q, VectorXd::Zero(n), k, c);
  // Orthonormal basis of ker J: the last n - rank right singular vectors.
  const Eigen::JacobiSVD<MatrixXd> svd(j, Eigen::ComputeFullV);
  const Eigen::Index rank = svd.rank();
  const MatrixXd basis = svd.matrixV().rightCols(n - rank);
  const MatrixXd ks = 0.5 * (k + k.transpose());
  const MatrixXd kr = basis.transpose() * ks * basis;
  const MatrixXd mr = basis.transpose() * v.mass(q) * basis;
  const Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> eig(kr, mr);
  if (eig.info() != Eigen::Success) throw std::runtime_error("eigen solver failed");
  return eig.eigenvalues().cwiseMax(0.0).cwiseSqrt() / (2.0 * std::numbers::pi);
}

void central_difference_tangent(TestVehicle& v, const VectorXd& q, const VectorXd& qd, double h_q,
                                double h_qd, MatrixXd& k, MatrixXd& c) {
  const Eigen::Index n = v.dofs();
  k.resize(n, n);
  c.resize(n, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    VectorXd qp = q, qm = q;
    qp(j) += h_q;
    qm(j) -= h_q;
    k.col(j) = -(v.forces(qp, qd) - v.forces(qm, qd)) / (2.0 * h_q);
    VectorXd vp = qd, vm = qd;
    vp(j) += h_qd;
    vm(j) -= h_qd;
    c.col(j) = -(v.forces(q, vp) - v.forces(q, vm)) / (2.0 * h_qd);
  }
}

}  // namespace rumble::test
