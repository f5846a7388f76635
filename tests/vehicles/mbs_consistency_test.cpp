// Internal consistency of mbs on a "zoo" vehicle that uses every feature: parent chains,
// rotations before translations, a DOF along a rotated x axis, z / x / line elements with
// preloads, loads and wheels on rotating bodies; and on the shipped vehicles.
#include <gtest/gtest.h>

#include <string>

#include "rigid_rail.hpp"
#include "vehicle_harness.hpp"

namespace rumble::test {
namespace {

/// gravity [m/s^2], damping of every element [N s/m], load on the tip [N].
std::string zoo(double gravity, double damping, double load) {
  const std::string c = std::to_string(damping);
  return R"({"gravity": )" + std::to_string(gravity) + R"(,
    "bodies": [
      {"name": "arm", "mass": 400, "inertia": 50, "transforms": [
        {"type": "tz", "value": -1.0, "dof": "z_arm"}, {"type": "ry", "value": 0.1, "dof": "p_arm"},
        {"type": "tx", "value": 1.2}, {"type": "tz", "value": 0.3}]},
      {"name": "link", "parent": "arm", "mass": 150,
       "inertia": [[30, 0, 1], [0, 20, 0], [1, 0, 25]], "transforms": [
        {"type": "tx", "value": 0.8}, {"type": "ry", "value": -0.2, "dof": "p_link"},
        {"type": "tx", "value": -0.5, "dof": "x_link"}]},
      {"name": "ws", "mass": 300, "transforms": [
        {"type": "tx", "value": 2.0}, {"type": "tz", "value": -0.4, "dof": "z_ws"}]},
      {"name": "tip", "parent": "link", "mass": 50, "inertia": 5, "transforms": [
        {"type": "ry", "value": 0.3}, {"type": "tz", "value": 0.2}]}],
    "elements": [
      {"name": "z", "body_a": "arm", "point_a": [0.5, 0.2], "body_b": "ws", "k": 1e6, "c": )" +
         c + R"(, "preload": 1e4},
      {"name": "line", "body_a": "reference", "point_a": [3, -2], "body_b": "link", "point_b": [0.3, 0.1],
       "direction": "line", "k": 2e5, "c": )" +
         c + R"(, "preload": -500},
      {"name": "x", "body_a": "arm", "point_a": [-0.5, 0], "body_b": "reference", "point_b": [-1, -1],
       "direction": "x", "k": 5e4, "c": )" +
         c + R"(},
      {"name": "tip", "body_a": "tip", "body_b": "ws", "point_b": [0.1, -0.1], "direction": "line",
       "k": 3e5, "c": )" +
         c + R"(}],
    "wheels": [{"body": "ws"}, {"body": "link", "point": [0.2, 0.3], "radius": 0.3}],
    "loads": [{"body": "tip", "point": [0.1, 0], "force": )" +
         std::to_string(load) + R"(}]})";
}

std::vector<std::string> all_vehicles() {
  return {zoo(9.81, 3e3, 2000), R"({"file": "half_train.json"})", R"({"file": "tram_t2000.json"})"};
}

TEST(MbsConsistency, MassMatrixIsSymmetricPositiveDefinite) {
  for (const std::string& params : all_vehicles()) {
    TestVehicle v("mbs", params);
    for (int trial = 0; trial < 10; ++trial) {
      const VectorXd q = 0.2 * VectorXd::Random(v.dofs());  // up to 0.2 m and 0.2 rad
      const MatrixXd m = v.mass(q);
      // Symmetric by construction (sum of J^T m J): exact equality is expected, allow 1 ulp.
      EXPECT_LE((m - m.transpose()).cwiseAbs().maxCoeff(), 1e-15 * m.cwiseAbs().maxCoeff());
      const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(m);
      EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0) << params;
    }
  }
}

TEST(MbsConsistency, TangentMatchesCentralDifferencesOfTheForces) {
  for (const std::string& params : all_vehicles()) {
    TestVehicle v("mbs", params);
    for (int trial = 0; trial < 3; ++trial) {
      const VectorXd q = 0.1 * VectorXd::Random(v.dofs());
      const VectorXd qd = 2.0 * VectorXd::Random(v.dofs());  // pitch rates up to 2 rad/s
      MatrixXd k, c, k_fd, c_fd;
      v.tangent(q, qd, k, c);
      // Central differences, h = 1e-6: truncation h^2 |f'''| / 6 and round-off eps |f| / h are
      // both ~1e-5 N/m against entries up to ~1e6 N/m; 1e-7 of the largest entry bounds them
      // with margin while any missing term (geometric stiffness of a preload, ~1e3 N/m) fails.
      central_difference_tangent(v, q, qd, 1e-6, 1e-6, k_fd, c_fd);
      EXPECT_LT((k - k_fd).cwiseAbs().maxCoeff(), 1e-7 * k.cwiseAbs().maxCoeff()) << params << "\n"
                                                                                  << k << "\n\n"
                                                                                  << k_fd;
      EXPECT_LT((c - c_fd).cwiseAbs().maxCoeff(), 1e-7 * c.cwiseAbs().maxCoeff()) << params << "\n"
                                                                                  << c << "\n\n"
                                                                                  << c_fd;
    }
  }
}

TEST(MbsConsistency, WheelJacobianMatchesCentralDifferences) {
  TestVehicle v("mbs", zoo(9.81, 3e3, 2000));
  VectorXd z0;
  MatrixXd j0;
  v.wheel_kinematics(VectorXd::Zero(v.dofs()), z0, j0);
  EXPECT_EQ(z0, VectorXd::Zero(2));  // z_w(0) = 0 by definition
  const VectorXd q = 0.2 * VectorXd::Random(v.dofs());
  VectorXd z, zp, zm;
  MatrixXd j, unused;
  v.wheel_kinematics(q, z, j);
  const double h = 1e-6;  // m or rad; error ~h^2 (1e-12 m) against entries ~1 m/m
  for (Eigen::Index k = 0; k < v.dofs(); ++k) {
    VectorXd qp = q, qm = q;
    qp(k) += h;
    qm(k) -= h;
    v.wheel_kinematics(qp, zp, unused);
    v.wheel_kinematics(qm, zm, unused);
    EXPECT_LT(((zp - zm) / (2 * h) - j.col(k)).cwiseAbs().maxCoeff(), 1e-8) << "dof " << k;
  }
}

/// Potential energy [J] of the undamped elements from their forces F = P - k d (outputs):
/// V = k d^2 / 2 - P d with d = (P - F) / k (s minus its nominal value).
double spring_energy(TestVehicle& v, const VectorXd& q, const double* k, const double* preload) {
  const VectorXd f = v.outputs(q, VectorXd::Zero(v.dofs()));
  double energy = 0.0;
  for (Eigen::Index e = 0; e < f.size(); ++e) {
    const double d = (preload[e] - f(e)) / k[e];
    energy += 0.5 * k[e] * d * d - preload[e] * d;
  }
  return energy;
}

TEST(MbsConsistency, FreeUndampedMotionConservesEnergy) {
  // No gravity, no load, no damping, no wheel contact: T + V is constant. T = q'^T M q' / 2 depends
  // on q through the rotations, so without the quadratic velocity terms (J' q') the energy changes
  // by ~150 % within this run (checked by deleting them); with them the drift is RK4's, O(h^4), far
  // below the 1e-8 tolerance for h = 1e-4 s.
  TestVehicle v("mbs", zoo(0.0, 0.0, 0.0));
  const double k[] = {1e6, 2e5, 5e4, 3e5};
  const double preload[] = {1e4, -500, 0, 0};
  const Eigen::Index n = v.dofs();
  VectorXd q = VectorXd::Zero(n);
  ASSERT_EQ(n, 5);
  VectorXd qd(5);
  qd << 0.3, 2.0, -3.0, 0.5, 0.1;  // m/s, rad/s
  const auto energy = [&](const VectorXd& x, const VectorXd& xd) {
    return 0.5 * xd.dot(v.mass(x) * xd) + spring_energy(v, x, k, preload);
  };
  const auto acceleration = [&](const VectorXd& x, const VectorXd& xd) -> VectorXd {
    return v.mass(x).llt().solve(v.forces(x, xd));
  };
  const double e0 = energy(q, qd);
  const double h = 1e-4;                     // s
  for (int step = 0; step < 5000; ++step) {  // 0.5 s, several periods of the stiffest mode
    const VectorXd a1 = acceleration(q, qd);
    const VectorXd v2 = qd + 0.5 * h * a1;
    const VectorXd a2 = acceleration(q + 0.5 * h * qd, v2);
    const VectorXd v3 = qd + 0.5 * h * a2;
    const VectorXd a3 = acceleration(q + 0.5 * h * v2, v3);
    const VectorXd v4 = qd + h * a3;
    const VectorXd a4 = acceleration(q + h * v3, v4);
    q += h / 6 * (qd + 2 * v2 + 2 * v3 + v4);
    qd += h / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
  }
  EXPECT_GT(q.cwiseAbs().maxCoeff(), 0.1);  // it did move (pitch ~ rate * time)
  EXPECT_NEAR(energy(q, qd), e0, 1e-8 * e0);
}

}  // namespace
}  // namespace rumble::test
