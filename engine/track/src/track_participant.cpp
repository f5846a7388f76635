// The track participant as the coupling sees it: built from its configuration, its footprints,
// their forces and motion across the interface, its energies for the checks and its state for
// checkpoints. How it finds its rest (track_statics.cpp) and how it steps (track_dynamics.cpp)
// are files of their own, so that each of the three reads alone.
#include "track/track_participant.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <utility>

#include "core/errors.hpp"
#include "track/hertz.hpp"
#include "track_participant_parts.hpp"
#include "track_spec/footprint_layout.hpp"

namespace rumble {
namespace {

std::vector<double> wheel_radii(const VehicleSet& vehicles) {
  std::vector<double> r(vehicles.wheel_count());
  for (std::size_t w = 0; w < r.size(); ++w) r[w] = vehicles.wheel_radius(w);
  return r;
}

}  // namespace

TrackParticipant::TrackParticipant(const TrackConfig& config, VehicleSet vehicles)
    : structure_(config),
      vehicles_(std::move(vehicles)),
      unevenness_(config.unevenness, wheel_radii(vehicles_), config.rail_start(),
                  config.rail_end()) {
  newmark_.gamma = config.newmark_gamma;
  newmark_.beta = 0.25 * (config.newmark_gamma + 0.5) * (config.newmark_gamma + 0.5);
  const std::size_t nw = vehicles_.wheel_count();
  hertz_.resize(nw);
  for (std::size_t w = 0; w < nw; ++w) {
    hertz_[w] = config.hertz_constant
                    ? *config.hertz_constant
                    : rumble::hertz_constant(vehicles_.wheel_radius(w), config.rail_radius,
                                             config.contact_E, config.contact_nu);
  }
  const auto nt = static_cast<Eigen::Index>(structure_.dof_count());
  const auto nv = static_cast<Eigen::Index>(vehicles_.dof_count());
  const auto nwi = static_cast<Eigen::Index>(nw);
  const std::size_t n = structure_.sleeper_count();
  for (Eigen::VectorXd* v : {&x_, &v_, &a_, &pa_t_, &pv_t_, &rhs_t_, &r_t_, &y_t_, &x_old_})
    v->setZero(nt);
  for (Eigen::VectorXd* v :
       {&q_, &qd_, &qdd_, &pa_v_, &pv_v_, &r_v_, &y_v_, &f_v_, &vel_v_, &acc_v_, &q_old_})
    v->setZero(nv);
  for (Eigen::VectorXd* v : {&z_w_, &s_rhs_, &s_sol_, &contact_force_linear_, &force_error_})
    v->setZero(nwi);
  a_track_ = BandedSymmetric(structure_.dof_count(), structure_.mass().half_bandwidth());
  a_track_operator_ = a_track_;
  a_vehicle_.setZero(nv, nv);
  lu_vehicle_ = Eigen::PartialPivLU<Eigen::MatrixXd>(nv);
  m_v_.setZero(nv, nv);
  k_v_.setZero(nv, nv);
  c_v_.setZero(nv, nv);
  j_w_.setZero(nwi, nv);
  z_t_.setZero(nt, nwi);
  // Two elements' DOFs per wheel: the one under it and the one it just left.
  inverse_columns_.resize(structure_.dof_count(), 8 * nw);
  z_v_.setZero(nv, nwi);
  s_small_.setZero(nwi, nwi);
  lu_small_ = Eigen::PartialPivLU<Eigen::MatrixXd>(nwi);
  contact_point_.resize(nw);
  contact_force_.assign(nw, 0.0);
  contact_stiffness_.assign(nw, 0.0);
  contact_delta_.assign(nw, 0.0);
  u_now_.assign(n, 0.0);
  v_now_.assign(n, 0.0);
  input_coeff_.assign(3 * 2 * n, 0.0);  // room for order 2: no allocation in set_input
  input_ = rumble_waveform{0, 2 * n, input_coeff_.data()};
  h_max_ = config.micro_step.value_or(0.0);
}

std::vector<rumble_footprint> TrackParticipant::footprints() const {
  return footprint_layout(structure_.config());
}

void TrackParticipant::footprint_forces(double* force) const {
  const TrackConfig& c = structure_.config();
  for (std::size_t i = 0; i < structure_.sleeper_count(); ++i) {
    const auto s = static_cast<Eigen::Index>(structure_.sleeper_dof(i));
    // Factor 2: the modelled rail is one of two symmetric rails on the same sleeper.
    force[i] = 2.0 * (c.ballast_k * (x_[s] - u_now_[i]) + c.ballast_c * (v_[s] - v_now_[i]));
  }
}

double TrackParticipant::rail_deflection_at(double x) const {
  return dot_rail(structure_.rail_point(x), x_);
}

void TrackParticipant::set_input(const rumble_waveform& motion) {
  const std::size_t n2 = 2 * structure_.sleeper_count();
  if (motion.n != n2 || motion.order > 2) {
    throw RunError("track input: expected " + std::to_string(n2) +
                   " channels (u then v per footprint) of order <= 2, got " +
                   std::to_string(motion.n) + " of order " + std::to_string(motion.order));
  }
  std::copy(motion.coeff, motion.coeff + (motion.order + 1) * n2, input_coeff_.begin());
  input_.order = motion.order;
}

void TrackParticipant::integrate_soil(std::unique_ptr<IntegratedSoil> soil) {
  soil_ = std::make_unique<SoilCondensation>(std::move(soil), structure_);
  h_factored_ = -1.0;  // the dynamic matrix now includes the soil
}

// --------------------------------------------------------------------------- energies

double TrackParticipant::track_energy() const {
  Eigen::VectorXd tmp(x_.size());
  structure_.mass().multiply(v_.data(), tmp.data());
  double e = 0.5 * v_.dot(tmp);
  structure_.stiffness().multiply(x_.data(), tmp.data());
  return e + 0.5 * x_.dot(tmp);
}

double TrackParticipant::vehicle_kinetic_energy() {
  vehicles_.mass(q_, m_v_);
  return 0.5 * qd_.dot(m_v_ * qd_);
}

double TrackParticipant::contact_energy() const {
  double e = 0.0;
  for (std::size_t w = 0; w < contact_delta_.size(); ++w)
    if (contact_delta_[w] > 0.0) e += 0.4 * hertz_[w] * std::pow(contact_delta_[w], 2.5);
  return e;
}

// --------------------------------------------------------------------------- checkpoints

std::size_t TrackParticipant::state_size() const {
  return 1 + 3 * static_cast<std::size_t>(x_.size() + q_.size()) + 2 * u_now_.size() +
         (soil_ ? soil_->soil().state_size() : 0);
}

void TrackParticipant::save_state(double* b) const {
  *b++ = t_;
  for (const Eigen::VectorXd* v : {&x_, &v_, &a_, &q_, &qd_, &qdd_})
    b = std::copy(v->data(), v->data() + v->size(), b);
  b = std::copy(u_now_.begin(), u_now_.end(), b);
  b = std::copy(v_now_.begin(), v_now_.end(), b);
  if (soil_) soil_->soil().save_state(b);
}

void TrackParticipant::restore_state(const double* b) {
  t_ = *b++;
  for (Eigen::VectorXd* v : {&x_, &v_, &a_, &q_, &qd_, &qdd_}) {
    std::copy(b, b + v->size(), v->data());
    b += v->size();
  }
  std::copy(b, b + u_now_.size(), u_now_.begin());
  b += u_now_.size();
  std::copy(b, b + v_now_.size(), v_now_.begin());
  b += v_now_.size();
  if (soil_) soil_->soil().restore_state(b);
  evaluate_contacts(t_, x_, q_);
}

}  // namespace rumble
