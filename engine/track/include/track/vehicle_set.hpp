// The vehicles on the track: their DOFs stacked into one vector, their wheels into one list, and
// the block-diagonal mass, forces, wheel kinematics and tangents evaluated through the plugins.
// All scratch space is allocated in finalize(); evaluations allocate nothing.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "plugin/instance.hpp"

namespace rumble {

class VehicleSet {
 public:
  struct Vehicle {
    std::unique_ptr<VehicleInstance> instance;
    std::string name;
    double speed = 0.0;  // m/s
    double start = 0.0;  // m, position of the vehicle reference at t = 0
    std::size_t dof_offset = 0;
    std::size_t wheel_offset = 0;
    // scratch, one block per vehicle
    Eigen::MatrixXd mass, stiffness, damping, jacobian;
    Eigen::VectorXd force, z, f_plus, f_minus, q_work, qd_work;
  };

  void add(std::unique_ptr<VehicleInstance> instance, std::string name, double speed, double start);

  std::size_t dof_count() const { return n_dof_; }
  std::size_t wheel_count() const { return n_wheels_; }
  const std::vector<Vehicle>& vehicles() const { return vehicles_; }
  /// Vehicle that owns global wheel w, and the wheel's index within it.
  std::pair<std::size_t, std::size_t> wheel_owner(std::size_t w) const { return wheel_owner_[w]; }

  double wheel_x(std::size_t w, double t) const;       // m, contact point along the track
  double wheel_rolled(std::size_t w, double t) const;  // m, distance rolled since t = 0
  double wheel_radius(std::size_t w) const;            // m

  void mass(const Eigen::VectorXd& q, Eigen::MatrixXd& m);
  void forces(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Eigen::VectorXd& f);
  /// z: n_wheels; jacobian: n_wheels x n_dof.
  void wheels(const Eigen::VectorXd& q, Eigen::VectorXd& z, Eigen::MatrixXd& jacobian);
  /// K = -df/dq, C = -df/dq'; analytic when the plugin offers it, else central differences.
  void tangent(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Eigen::MatrixXd& k,
               Eigen::MatrixXd& c);

 private:
  void finalize();  // offsets and scratch space, redone on every add()
  std::vector<Vehicle> vehicles_;
  std::vector<std::pair<std::size_t, std::size_t>> wheel_owner_;
  std::size_t n_dof_ = 0;
  std::size_t n_wheels_ = 0;
};

}  // namespace rumble
