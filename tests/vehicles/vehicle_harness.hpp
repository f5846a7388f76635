// vehicle_harness.hpp: drive a vehicle plugin through its C table, as the engine does.
#pragma once

#include <rumble/abi.h>

#include <Eigen/Dense>
#include <string>
#include <vector>

namespace rumble::test {

using Eigen::MatrixXd;
using Eigen::VectorXd;

/// Directory of the shipped vehicle definitions (scenarios/vehicles), used as scenario_dir.
std::string vehicles_dir();
/// Text of a file (a shipped definition), for tests that edit it.
std::string read_text(const std::string& path);

/// The error message create() returns for these params ("" when it succeeds).
std::string creation_error(const std::string& type, const std::string& params_json,
                           const std::string& scenario_dir = vehicles_dir());

/// One vehicle instance created by the plugin's factory; every call must return RUMBLE_OK.
class TestVehicle {
 public:
  TestVehicle(const std::string& type, const std::string& params_json,
              const std::string& scenario_dir = vehicles_dir());
  ~TestVehicle();
  TestVehicle(const TestVehicle&) = delete;
  TestVehicle& operator=(const TestVehicle&) = delete;

  Eigen::Index dofs() const { return n_; }
  Eigen::Index wheel_count() const { return static_cast<Eigen::Index>(wheels_.size()); }
  const std::vector<rumble_wheel>& wheels() const { return wheels_; }

  MatrixXd mass(const VectorXd& q);
  VectorXd forces(const VectorXd& q, const VectorXd& qd);
  /// z_w(q) [m] and J (n_wheels x n_dof).
  void wheel_kinematics(const VectorXd& q, VectorXd& z, MatrixXd& jacobian);
  /// K = -df/dq, C = -df/dq' from the plugin.
  void tangent(const VectorXd& q, const VectorXd& qd, MatrixXd& k, MatrixXd& c);
  std::vector<std::string> output_names();
  VectorXd outputs(const VectorXd& q, const VectorXd& qd);

 private:
  void check(rumble_status status, const char* call) const;
  const rumble_vehicle_api* api_ = nullptr;
  rumble_instance* self_ = nullptr;
  std::string scenario_dir_;  // outlives the instance: rumble_host points into it
  rumble_host host_{};
  Eigen::Index n_ = 0;
  std::vector<rumble_wheel> wheels_;
};

}  // namespace rumble::test
