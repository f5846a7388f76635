#include "track/vehicle_set.hpp"

#include <cmath>

namespace rumble {

void VehicleSet::add(std::unique_ptr<VehicleInstance> instance, std::string name, double speed,
                     double start) {
  Vehicle v;
  v.instance = std::move(instance);
  v.name = std::move(name);
  v.speed = speed;
  v.start = start;
  vehicles_.push_back(std::move(v));
  finalize();
}

void VehicleSet::finalize() {
  n_dof_ = 0;
  n_wheels_ = 0;
  wheel_owner_.clear();
  for (std::size_t i = 0; i < vehicles_.size(); ++i) {
    Vehicle& v = vehicles_[i];
    const auto n = static_cast<Eigen::Index>(v.instance->dof_count());
    const auto nw = static_cast<Eigen::Index>(v.instance->wheels().size());
    v.dof_offset = n_dof_;
    v.wheel_offset = n_wheels_;
    v.mass.setZero(n, n);
    v.stiffness.setZero(n, n);
    v.damping.setZero(n, n);
    v.jacobian.setZero(nw, n);
    v.force.setZero(n);
    v.f_plus.setZero(n);
    v.f_minus.setZero(n);
    v.q_work.setZero(n);
    v.qd_work.setZero(n);
    v.z.setZero(nw);
    for (Eigen::Index k = 0; k < nw; ++k) wheel_owner_.emplace_back(i, static_cast<std::size_t>(k));
    n_dof_ += static_cast<std::size_t>(n);
    n_wheels_ += static_cast<std::size_t>(nw);
  }
}

double VehicleSet::wheel_x(std::size_t w, double t) const {
  const auto [i, k] = wheel_owner_[w];
  const Vehicle& v = vehicles_[i];
  return v.start + v.speed * t + v.instance->wheels()[k].offset;
}

double VehicleSet::wheel_rolled(std::size_t w, double t) const {
  return vehicles_[wheel_owner_[w].first].speed * t;
}

double VehicleSet::wheel_radius(std::size_t w) const {
  const auto [i, k] = wheel_owner_[w];
  return vehicles_[i].instance->wheels()[k].radius;
}

void VehicleSet::mass(const Eigen::VectorXd& q, Eigen::MatrixXd& m) {
  for (Vehicle& v : vehicles_) {
    const auto n = v.mass.rows();
    const auto o = static_cast<Eigen::Index>(v.dof_offset);
    v.q_work = q.segment(o, n);
    v.instance->mass_matrix(v.q_work.data(), v.mass.data());
    m.block(o, o, n, n) = v.mass;
  }
}

void VehicleSet::forces(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                        Eigen::VectorXd& f) {
  for (Vehicle& v : vehicles_) {
    const auto n = v.force.size();
    const auto o = static_cast<Eigen::Index>(v.dof_offset);
    v.q_work = q.segment(o, n);
    v.qd_work = qd.segment(o, n);
    v.instance->forces(t, v.q_work.data(), v.qd_work.data(), v.force.data());
    f.segment(o, n) = v.force;
  }
}

void VehicleSet::wheels(const Eigen::VectorXd& q, Eigen::VectorXd& z, Eigen::MatrixXd& jacobian) {
  jacobian.setZero();
  for (Vehicle& v : vehicles_) {
    const auto n = v.force.size();
    const auto nw = v.z.size();
    const auto o = static_cast<Eigen::Index>(v.dof_offset);
    const auto ow = static_cast<Eigen::Index>(v.wheel_offset);
    v.q_work = q.segment(o, n);
    v.instance->wheel_kinematics(v.q_work.data(), v.z.data(), v.jacobian.data());
    z.segment(ow, nw) = v.z;
    jacobian.block(ow, o, nw, n) = v.jacobian;
  }
}

void VehicleSet::tangent(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                         Eigen::MatrixXd& k, Eigen::MatrixXd& c) {
  k.setZero();
  c.setZero();
  for (Vehicle& v : vehicles_) {
    const auto n = v.force.size();
    const auto o = static_cast<Eigen::Index>(v.dof_offset);
    v.q_work = q.segment(o, n);
    v.qd_work = qd.segment(o, n);
    if (!v.instance->tangent(t, v.q_work.data(), v.qd_work.data(), v.stiffness.data(),
                             v.damping.data())) {
      // Central differences; steps relative to the scale of the coordinate, floor 1e-7 (m or
      // rad), so that truncation (O(eps^2)) and round-off (O(1e-16 |f| / eps)) both stay small.
      for (Eigen::Index j = 0; j < n; ++j) {
        for (int which = 0; which < 2; ++which) {
          Eigen::VectorXd& x = which == 0 ? v.q_work : v.qd_work;
          Eigen::MatrixXd& out = which == 0 ? v.stiffness : v.damping;
          const double x0 = x[j];
          const double eps = 1e-7 * std::max(1.0, std::abs(x0));
          x[j] = x0 + eps;
          v.instance->forces(t, v.q_work.data(), v.qd_work.data(), v.f_plus.data());
          x[j] = x0 - eps;
          v.instance->forces(t, v.q_work.data(), v.qd_work.data(), v.f_minus.data());
          x[j] = x0;
          out.col(j) = -(v.f_plus - v.f_minus) / (2.0 * eps);
        }
      }
    }
    k.block(o, o, n, n) = v.stiffness;
    c.block(o, o, n, n) = v.damping;
  }
}

}  // namespace rumble
