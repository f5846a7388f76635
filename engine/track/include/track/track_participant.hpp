// The vehicle/track participant: rail + sleepers + ballast (TrackStructure), the vehicles
// (VehicleSet) and the Hertz wheel/rail contacts, integrated monolithically with Newmark and a
// Newton iteration on the contact. Its interface with the soil is the footprint layout:
//   output  F_i = 2 [k_b (s_i - u_i) + c_b (s_i' - v_i)]  [N]  (whole sleeper: both rails)
//   input   u_i, v_i  [m, m/s]  as a waveform over the macro step
//
// Each Newton iteration solves (D + B K_c B^T) dx = r, where D = diag(A_track, A_vehicle) is the
// linear part (A_track banded and factored once per micro-step size) and B K_c B^T the contact
// stiffness (one column per wheel), by the Woodbury identity: 1 + n_wheels banded solves, a
// small dense solve for the vehicles, and an n_wheels x n_wheels system. No allocation per step.
#pragma once

#include <rumble/abi.h>

#include <Eigen/Dense>
#include <cstdint>
#include <functional>
#include <memory>
#include <rumble/newmark.hpp>
#include <vector>

#include "track/integrated_soil.hpp"
#include "track/inverse_columns.hpp"
#include "track/soil_condensation.hpp"
#include "track/track_structure.hpp"
#include "track/unevenness.hpp"
#include "track/vehicle_set.hpp"

namespace rumble {

class TrackParticipant {
 public:
  /// Soil statics: given whole-sleeper footprint forces F [N], return footprint displacements u
  /// [m].
  using SoilStatics = std::function<void(const std::vector<double>& force, std::vector<double>& u)>;

  TrackParticipant(const TrackConfig& config, VehicleSet vehicles);

  const TrackStructure& structure() const { return structure_; }
  const VehicleSet& vehicles() const { return vehicles_; }
  std::vector<rumble_footprint> footprints() const;
  std::size_t interface_size() const { return structure_.sleeper_count(); }
  double hertz_constant(std::size_t wheel) const { return hertz_[wheel]; }
  /// Largest micro-step [s]: the scenario's, or 1/20 of the period of the wheel-on-rail
  /// contact resonance (wheel mass against rail mass over one bay, linearized Hertz spring).
  double micro_step_limit() const { return h_max_; }
  /// The one micro-step rule: a macro step H [s] is taken in ceil(H / micro_step_limit())
  /// equal micro-steps (at least one); this is their number. Throws RunError beyond
  /// kMaxMicroStepsPerMacroStep (a step size that cannot be meant).
  std::int64_t micro_steps(double H) const;
  static constexpr double kMaxMicroStepsPerMacroStep = 1e7;

  /// Integrates a linear soil with the track as one system (the monolithic reference, decision
  /// 0008): from then on the footprint motion is the integrated soil's and set_input is not
  /// used; the statics are still the soil's own (solve_static's function), and the integrated
  /// soil starts at rest there (IntegratedSoil::start_static). Before solve_static.
  void integrate_soil(std::unique_ptr<IntegratedSoil> soil);
  bool has_integrated_soil() const { return soil_ != nullptr; }

  /// Static equilibrium under the vehicles' weight, iterated with the soil to consistency;
  /// with no soil (empty function) the footprints are fixed. Returns the iterations used.
  int solve_static(const SoilStatics& soil);
  /// With an integrated soil after solve_static: how far the soil's statics hold footprint i
  /// beyond its matrices' K^-1 B F [m] (IntegratedSoil::static_offset).
  double integrated_static_offset(std::size_t i) const { return soil_->soil().static_offset(i); }

  /// Footprint motion over the next macro step: 2n channels (u_0..u_{n-1}, v_0..v_{n-1}).
  void set_input(const rumble_waveform& motion);
  /// Advances from time() to t + H in micro-steps of at most micro_step_limit().
  void advance(double t, double H);
  double time() const { return t_; }

  // ---- outputs at the current time
  void footprint_forces(double* force) const;                                      // n values [N]
  double contact_force(std::size_t wheel) const { return contact_force_[wheel]; }  // N
  double wheel_x(std::size_t wheel) const { return vehicles_.wheel_x(wheel, t_); }
  double rail_deflection_at(double x) const;  // m
  const Eigen::VectorXd& vehicle_q() const { return q_; }
  const Eigen::VectorXd& vehicle_qd() const { return qd_; }
  const Eigen::VectorXd& track_x() const { return x_; }
  const Eigen::VectorXd& track_v() const { return v_; }
  double footprint_u(std::size_t i) const { return u_now_[i]; }
  double footprint_v(std::size_t i) const { return v_now_[i]; }
  int newton_iterations_last_step() const { return last_iterations_; }

  /// Energies for checks [J]: track kinetic + strain (footprints at rest), vehicle kinetic,
  /// contact (Hertz potential 2/5 C_H delta^2.5).
  double track_energy() const;
  double vehicle_kinetic_energy();
  double contact_energy() const;

  // ---- checkpointing (coupler save/restore)
  std::size_t state_size() const;
  void save_state(double* buffer) const;
  void restore_state(const double* buffer);

 private:
  void factorize_dynamic(double h);
  void micro_step(double t1, double h, double tau);
  // The steps of micro_step: the footprint motion at tau of the input waveform, the Newmark
  // predictors (the step's start), the track's responses to unit contact forces, a Newton
  // iteration's residuals and its update (Woodbury), and the Newmark correctors.
  void footprint_motion_at(double tau);
  void predict(double h);
  void unit_contact_responses();
  void newton_residuals(double t1, int it, double ca, double cv);
  void newton_update(int it, double ca, double cv);
  void correct(double t1, double h);
  // The steps of solve_static: the wheels on the rail at t = 0, the track's responses K^-1 N_w
  // to unit wheel loads, the state at rest, and the micro-step the contact frequency allows.
  void place_wheels_at_rest();
  Eigen::MatrixXd unit_wheel_load_responses(const BandedSymmetric& k_static) const;
  void start_at_rest(const Eigen::VectorXd& x, const Eigen::VectorXd& q, const Eigen::VectorXd& F,
                     const std::vector<double>& u, const std::vector<double>& fb);
  double contact_step_limit(const Eigen::VectorXd& q, const Eigen::VectorXd& F);
  /// Contact forces and stiffnesses for the rail state x and wheel positions z.
  void evaluate_contacts(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& q);
  void ballast_load(double* f) const;  // k_b u + c_b v on the sleeper DOFs
  /// y = A^-1 y with the factored dynamic matrix (and the integrated soil condensed on it).
  void solve_linear(double* y) const;

  TrackStructure structure_;
  VehicleSet vehicles_;
  Unevenness unevenness_;
  Newmark newmark_;
  std::vector<double> hertz_;  // N/m^1.5 per wheel
  double h_max_ = 0.0;
  double t_ = 0.0;

  // State.
  Eigen::VectorXd x_, v_, a_;     // track
  Eigen::VectorXd q_, qd_, qdd_;  // vehicles
  // Footprint motion: input waveform and its value at the current time.
  std::vector<double> input_coeff_;
  rumble_waveform input_{0, 0, nullptr};
  double input_t0_ = 0.0, input_H_ = 1.0;
  std::vector<double> u_now_, v_now_;

  // Dynamic factorization for the current micro-step size.
  double h_factored_ = -1.0;
  BandedSymmetric a_track_operator_;  // K + c_v C + c_a M, for residuals
  BandedSymmetric a_track_;           // its Cholesky factor
  InverseColumns inverse_columns_;    // columns of A^-1 under the wheels
  Eigen::MatrixXd a_vehicle_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_vehicle_;
  std::unique_ptr<SoilCondensation> soil_;  // the integrated soil, if any (monolithic)

  // Per-step work space.
  Eigen::VectorXd pa_t_, pv_t_, rhs_t_, r_t_, y_t_, pa_v_, pv_v_, r_v_, y_v_, f_v_, z_w_, vel_v_,
      acc_v_, x_old_, q_old_;
  Eigen::MatrixXd m_v_, k_v_, c_v_, j_w_, z_t_, z_v_, s_small_;
  Eigen::VectorXd s_rhs_, s_sol_;
  Eigen::VectorXd contact_force_linear_, force_error_;  // N, per wheel
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_small_;
  std::vector<TrackStructure::RailPoint> contact_point_;
  std::vector<double> contact_force_, contact_stiffness_, contact_delta_;
  int last_iterations_ = 0;
};

}  // namespace rumble
