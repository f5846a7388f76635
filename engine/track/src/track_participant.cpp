#include "track/track_participant.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "core/errors.hpp"
#include "track/footprint_flexibility.hpp"
#include "track/hertz.hpp"
#include "track/static_interface.hpp"
#include "track_spec/footprint_layout.hpp"

namespace rumble {
namespace {

constexpr int kMaxNewtonIterations = 30;
// Newton (dynamics: residual forces; statics: updates) stops below this fraction of its scale:
// far below any physical effect, far above round-off (~1e-16 relative).
constexpr double kRelativeTolerance = 1e-10;
// Micro-steps per period of the highest resolved resonance (wheel/rail contact, P1).
constexpr double kStepsPerContactPeriod = 20.0;

double max_abs(const Eigen::VectorXd& v) {
  return v.size() == 0 ? 0.0 : v.cwiseAbs().maxCoeff();
}

// Ref, not const VectorXd&: a column of z_t_ binds without a temporary copy (an allocation).
double dot_rail(const TrackStructure::RailPoint& p, const Eigen::Ref<const Eigen::VectorXd>& x) {
  double w = 0.0;
  for (std::size_t k = 0; k < 4; ++k) w += p.shape[k] * x[static_cast<Eigen::Index>(p.dof[k])];
  return w;
}

std::vector<double> wheel_radii(const VehicleSet& vehicles) {
  std::vector<double> r(vehicles.wheel_count());
  for (std::size_t w = 0; w < r.size(); ++w) r[w] = vehicles.wheel_radius(w);
  return r;
}

/// The vehicles at rest on the rail (statics): Newton on r1 = f(q) - J^T F = 0 (vehicle
/// equilibrium) and r2 = z(q) - w(F) - r - (F/C)^(2/3) = 0 (Hertz compatibility) for the vehicle
/// DOFs q and the wheel loads F, the rail under the wheels at w(F) = G F + w0.
class WheelsAtRest {
 public:
  WheelsAtRest(VehicleSet& vehicles, const std::vector<double>& hertz, const Eigen::MatrixXd& G,
               const Eigen::VectorXd& rough, double weight)
      : vehicles_(vehicles),
        hertz_(hertz),
        G_(G),
        rough_(rough),
        weight_(weight),
        nv_(static_cast<Eigen::Index>(vehicles.dof_count())),
        nw_(static_cast<Eigen::Index>(vehicles.wheel_count())),
        zero_(Eigen::VectorXd::Zero(nv_)) {}

  /// From (q, F) to the rest state over the rail's own deflection w0 [m] under the wheels;
  /// throws RunError when Newton does not converge or a wheel carries no load.
  void solve(const Eigen::VectorXd& w0, Eigen::VectorXd& q, Eigen::VectorXd& F) const {
    const Eigen::Index m = nv_ + nw_;
    Eigen::VectorXd r(m), dy(m);
    Eigen::MatrixXd jac(m, m);
    bool converged = false;
    for (int it = 0; it < kMaxNewtonIterations && !converged; ++it) {
      residual(q, F, w0, r);
      jacobian(q, F, w0, jac);
      dy = jac.fullPivLu().solve(r);
      q -= dy.head(nv_);
      F -= dy.tail(nw_);
      // Displacement scale at least 1 mm (or 1 mrad): preloaded vehicles rest near q = 0.
      converged =
          dy.head(nv_).cwiseAbs().maxCoeff() <= kRelativeTolerance * std::max(max_abs(q), 1e-3) &&
          dy.tail(nw_).cwiseAbs().maxCoeff() <= kRelativeTolerance * weight_;
    }
    if (!converged) throw RunError("track statics: Newton on the wheel loads did not converge");
    for (Eigen::Index w = 0; w < nw_; ++w) {
      if (F[w] <= 0.0) {
        throw RunError("track statics: wheel " + std::to_string(w) +
                       " carries no load at rest (F = " + std::to_string(F[w]) +
                       " N); check the vehicle's masses and geometry");
      }
    }
  }

 private:
  void residual(const Eigen::VectorXd& q, const Eigen::VectorXd& F, const Eigen::VectorXd& w0,
                Eigen::VectorXd& out) const {
    Eigen::VectorXd f(nv_), z(nw_);
    Eigen::MatrixXd J(nw_, nv_);
    vehicles_.forces(0.0, q, zero_, f);
    vehicles_.wheels(q, z, J);
    out.head(nv_) = f - J.transpose() * F;
    const Eigen::VectorXd wr = G_ * F + w0;
    for (Eigen::Index w = 0; w < nw_; ++w) {
      const double Fw = std::max(F[w], 1e-12 * weight_);
      out[nv_ + w] =
          z[w] - wr[w] - rough_[w] - std::pow(Fw / hertz_[static_cast<std::size_t>(w)], 2.0 / 3.0);
    }
  }

  /// d r / d(q, F): d/dq by central differences (statics run once), d/dF exact.
  void jacobian(const Eigen::VectorXd& q, const Eigen::VectorXd& F, const Eigen::VectorXd& w0,
                Eigen::MatrixXd& jac) const {
    const Eigen::Index m = nv_ + nw_;
    Eigen::VectorXd rp(m), rm(m), z(nw_);
    Eigen::MatrixXd J(nw_, nv_);
    for (Eigen::Index j = 0; j < nv_; ++j) {
      const double eps = 1e-8 * std::max(1.0, std::abs(q[j]));
      Eigen::VectorXd qp = q, qm = q;
      qp[j] += eps;
      qm[j] -= eps;
      residual(qp, F, w0, rp);
      residual(qm, F, w0, rm);
      jac.col(j) = (rp - rm) / (2.0 * eps);
    }
    vehicles_.wheels(q, z, J);
    jac.block(0, nv_, nv_, nw_) = -J.transpose();
    jac.block(nv_, nv_, nw_, nw_) = -G_;
    for (Eigen::Index w = 0; w < nw_; ++w) {
      const double Fw = std::max(F[w], 1e-12 * weight_);
      const double C = hertz_[static_cast<std::size_t>(w)];
      jac(nv_ + w, nv_ + w) -= (2.0 / 3.0) * std::pow(C, -2.0 / 3.0) * std::pow(Fw, -1.0 / 3.0);
    }
  }

  VehicleSet& vehicles_;
  const std::vector<double>& hertz_;  // N/m^1.5 per wheel
  const Eigen::MatrixXd& G_;          // m/N: rail deflection under wheel w per unit load at j
  const Eigen::VectorXd& rough_;      // m, the unevenness under each wheel
  const double weight_;               // N, the load scale
  const Eigen::Index nv_, nw_;
  const Eigen::VectorXd zero_;  // the vehicles' velocities at rest
};

/// The wheel loads Newton starts from: least squares J^T F = f(q) at q = 0, each at least 1e-3
/// of the largest (a wheel with no load has no Hertz compliance). Returns the load scale [N].
double initial_wheel_loads(VehicleSet& vehicles, Eigen::VectorXd& F) {
  const auto nv = static_cast<Eigen::Index>(vehicles.dof_count());
  const auto nw = static_cast<Eigen::Index>(vehicles.wheel_count());
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(nv), zero = Eigen::VectorXd::Zero(nv);
  Eigen::VectorXd f(nv), z(nw);
  Eigen::MatrixXd J(nw, nv);
  vehicles.forces(0.0, q, zero, f);
  vehicles.wheels(q, z, J);
  F = (J * J.transpose()).ldlt().solve(J * f);
  const double weight = std::max(F.cwiseAbs().maxCoeff(), 1.0);  // N, scale only
  for (Eigen::Index w = 0; w < nw; ++w) F[w] = std::max(F[w], 1e-3 * weight);
  return weight;
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

void TrackParticipant::ballast_load(double* f) const {
  const TrackConfig& c = structure_.config();
  for (std::size_t i = 0; i < structure_.sleeper_count(); ++i)
    f[structure_.sleeper_dof(i)] += c.ballast_k * u_now_[i] + c.ballast_c * v_now_[i];
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

void TrackParticipant::solve_linear(double* y) const {
  a_track_.solve(y);
  if (soil_) soil_->correct_solve(y);
}

// --------------------------------------------------------------------------- statics

int TrackParticipant::solve_static(const SoilStatics& soil) {
  const TrackConfig& c = structure_.config();
  const std::size_t n = structure_.sleeper_count();
  const auto nt = static_cast<Eigen::Index>(structure_.dof_count());
  const auto nwi = static_cast<Eigen::Index>(vehicles_.wheel_count());

  BandedSymmetric k_static = structure_.stiffness();
  if (!k_static.factorize()) throw RunError("track statics: the track stiffness is singular");
  place_wheels_at_rest();
  const Eigen::MatrixXd g = unit_wheel_load_responses(k_static);
  Eigen::MatrixXd G(nwi, nwi);
  for (Eigen::Index w = 0; w < nwi; ++w)
    for (Eigen::Index j = 0; j < nwi; ++j)
      G(w, j) = dot_rail(contact_point_[static_cast<std::size_t>(w)], g.col(j));
  Eigen::VectorXd rough(nwi);
  for (std::size_t w = 0; w < vehicles_.wheel_count(); ++w)
    rough[static_cast<Eigen::Index>(w)] = unevenness_.at(w, vehicles_.wheel_x(w, 0.0), 0.0);

  // Unknowns y = (q, F), starting from q = 0 and the least-squares loads.
  Eigen::VectorXd q = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(vehicles_.dof_count()));
  Eigen::VectorXd F(nwi);
  const double weight = initial_wheel_loads(vehicles_, F);
  const WheelsAtRest wheels_at_rest(vehicles_, hertz_, G, rough, weight);

  Eigen::VectorXd sol0(nt), x(nt), w0(nwi);
  // The track's side of the static problem: the footprint forces fb [N] (both rails) for the
  // footprint settlements u [m], with the vehicles in equilibrium on the rail (q, F, x follow
  // the last call).
  const InterfaceMap track_forces = [&](const std::vector<double>& u, std::vector<double>& fb) {
    sol0.setZero();
    for (std::size_t i = 0; i < n; ++i)
      sol0[static_cast<Eigen::Index>(structure_.sleeper_dof(i))] = c.ballast_k * u[i];
    k_static.solve(sol0.data());
    for (std::size_t w = 0; w < vehicles_.wheel_count(); ++w)
      w0[static_cast<Eigen::Index>(w)] = dot_rail(contact_point_[w], sol0);
    wheels_at_rest.solve(w0, q, F);
    x = sol0 + g * F;
    fb.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      fb[i] = 2.0 * c.ballast_k * (x[static_cast<Eigen::Index>(structure_.sleeper_dof(i))] - u[i]);
  };
  std::vector<double> u(n, 0.0), fb(n, 0.0);
  int soil_solves = 0;
  if (soil) {
    soil_solves = solve_interface_statics(track_forces, soil,
                                          half_space_flexibility_shape(footprints()), u, fb)
                      .soil_solves;
  } else {
    track_forces(u, fb);  // footprints fixed: the track alone
  }
  start_at_rest(x, q, F, u, fb);
  if (!c.micro_step) h_max_ = contact_step_limit(q, F);
  return soil ? soil_solves : 1;
}

void TrackParticipant::place_wheels_at_rest() {
  const TrackConfig& c = structure_.config();
  for (std::size_t w = 0; w < vehicles_.wheel_count(); ++w) {
    const double xw = vehicles_.wheel_x(w, 0.0);
    if (!structure_.on_rail(xw)) {
      std::ostringstream m;
      m << "wheel " << w << " is at x = " << xw << " m at t = 0, off the rail [" << c.rail_start()
        << ", " << c.rail_end() << "] m";
      throw ConfigError(m.str());
    }
    contact_point_[w] = structure_.rail_point(xw);
  }
}

Eigen::MatrixXd TrackParticipant::unit_wheel_load_responses(const BandedSymmetric& k_static) const {
  const std::size_t nw = vehicles_.wheel_count();
  // g_w = K^-1 N_w: the track's response to a unit force at each wheel.
  Eigen::MatrixXd g(static_cast<Eigen::Index>(structure_.dof_count()),
                    static_cast<Eigen::Index>(nw));
  g.setZero();
  for (std::size_t w = 0; w < nw; ++w) {
    for (std::size_t k = 0; k < 4; ++k)
      g(static_cast<Eigen::Index>(contact_point_[w].dof[k]), static_cast<Eigen::Index>(w)) +=
          contact_point_[w].shape[k];
    k_static.solve(g.col(static_cast<Eigen::Index>(w)).data());
  }
  return g;
}

void TrackParticipant::start_at_rest(const Eigen::VectorXd& x, const Eigen::VectorXd& q,
                                     const Eigen::VectorXd& F, const std::vector<double>& u,
                                     const std::vector<double>& fb) {
  const std::size_t n = structure_.sleeper_count();
  x_ = x;
  v_.setZero();
  a_.setZero();
  q_ = q;
  qd_.setZero();
  qdd_.setZero();
  u_now_ = u;
  if (soil_) {  // the soil at rest under the final footprint forces, where its statics put it
    soil_->soil().start_static(fb.data(), u.data());
    for (std::size_t i = 0; i < n; ++i) u_now_[i] = soil_->soil().footprint_u(i);
  }
  std::fill(v_now_.begin(), v_now_.end(), 0.0);
  std::fill(input_coeff_.begin(), input_coeff_.end(), 0.0);
  std::copy(u.begin(), u.end(), input_coeff_.begin());  // hold the static footprint position
  input_.order = 0;
  t_ = 0.0;
  for (std::size_t w = 0; w < vehicles_.wheel_count(); ++w)
    contact_force_[w] = F[static_cast<Eigen::Index>(w)];
}

double TrackParticipant::contact_step_limit(const Eigen::VectorXd& q, const Eigen::VectorXd& F) {
  const TrackConfig& c = structure_.config();
  const auto nv = static_cast<Eigen::Index>(vehicles_.dof_count());
  const auto nwi = static_cast<Eigen::Index>(vehicles_.wheel_count());
  // P1-type resonance: linearized Hertz spring between the wheel's effective mass and the
  // rail mass of one bay.
  Eigen::MatrixXd M(nv, nv), J(nwi, nv);
  Eigen::VectorXd z(nwi);
  M.setZero();
  vehicles_.mass(q, M);
  vehicles_.wheels(q, z, J);
  const Eigen::MatrixXd mobility = J * M.ldlt().solve(J.transpose());
  const double rail_mass = c.rail_mass_per_length * c.sleeper_spacing;
  double f_max = 0.0;  // Hz
  for (Eigen::Index w = 0; w < nwi; ++w) {
    const double k_h = linearized_stiffness(hertz_[static_cast<std::size_t>(w)], F[w]);
    const double inv_mass = mobility(w, w) + 1.0 / rail_mass;
    f_max = std::max(f_max, std::sqrt(k_h * inv_mass) / (2.0 * std::numbers::pi));
  }
  // A wheel mass of 1e-300 kg (or a contact of no stiffness) gives no finite frequency, and no
  // micro-step follows from it: say which input, not "advance() before solve_static()".
  if (!(std::isfinite(f_max) && f_max > 0.0)) {
    std::ostringstream m;
    m << "track: no finite wheel/rail contact frequency (" << f_max
      << " Hz) follows from the vehicles' masses and the Hertz contact: check every vehicle's "
         "masses (e.g. a wheel mass of 1e-300 kg), or set /track/integrator/micro_step";
    throw RunError(m.str());
  }
  return 1.0 / (kStepsPerContactPeriod * f_max);
}

// --------------------------------------------------------------------------- dynamics

void TrackParticipant::factorize_dynamic(double h) {
  if (h == h_factored_) return;
  a_track_operator_.set_combination(1.0, structure_.stiffness(), newmark_.c_v(h),
                                    structure_.damping(), newmark_.c_a(h), structure_.mass());
  a_track_ = a_track_operator_;
  if (!a_track_.factorize()) throw RunError("track: dynamic matrix is not positive definite");
  if (soil_) soil_->factorize(newmark_, h, a_track_);
  inverse_columns_.clear();
  h_factored_ = h;
}

void TrackParticipant::evaluate_contacts(double t, const Eigen::VectorXd& x,
                                         const Eigen::VectorXd& q) {
  vehicles_.wheels(q, z_w_, j_w_);
  for (std::size_t w = 0; w < vehicles_.wheel_count(); ++w) {
    const double xw = vehicles_.wheel_x(w, t);
    if (!structure_.on_rail(xw)) {
      std::ostringstream m;
      m << "wheel " << w << " left the rail at t = " << t << " s (x = " << xw
        << " m); shorten time.end or lengthen the track (track.sleepers.count)";
      throw RunError(m.str());
    }
    contact_point_[w] = structure_.rail_point(xw);
    const double delta = z_w_[static_cast<Eigen::Index>(w)] - dot_rail(contact_point_[w], x) -
                         unevenness_.at(w, xw, vehicles_.wheel_rolled(w, t));
    contact_delta_[w] = delta;
    if (delta > 0.0) {
      const double root = std::sqrt(delta);
      contact_force_[w] = hertz_[w] * delta * root;    // C_H delta^1.5
      contact_stiffness_[w] = 1.5 * hertz_[w] * root;  // dF/d delta
    } else {
      contact_force_[w] = 0.0;  // loss of contact: no tension
      contact_stiffness_[w] = 0.0;
    }
  }
}

std::int64_t TrackParticipant::micro_steps(double H) const {
  if (!(h_max_ > 0.0)) throw RunError("track: advance() before solve_static()");
  // Counted in floating point first: a tiny micro-step must not overflow the integer count.
  const double n = std::max(std::ceil(H / h_max_ - 1e-9), 1.0);
  if (!(n <= kMaxMicroStepsPerMacroStep)) {
    std::ostringstream m;
    m << "track: a macro step of " << H << " s in micro-steps of " << h_max_ << " s is " << n
      << " micro-steps, more than " << kMaxMicroStepsPerMacroStep
      << "; raise /track/integrator/micro_step or lower /time/macro_step";
    throw RunError(m.str());
  }
  return static_cast<std::int64_t>(n);
}

void TrackParticipant::advance(double t, double H) {
  const std::int64_t n_sub = micro_steps(H);
  const double h = H / static_cast<double>(n_sub);
  factorize_dynamic(h);
  input_t0_ = t;
  input_H_ = H;
  for (std::int64_t s = 1; s <= n_sub; ++s) {
    const double tau = static_cast<double>(s) / static_cast<double>(n_sub);
    micro_step(t + tau * H, h, tau);
  }
  t_ = t + H;
}

void TrackParticipant::micro_step(double t1, double h, double tau) {
  // Footprint motion at t1 from the input waveform; an integrated soil's comes from the joint
  // solve instead.
  if (!soil_) footprint_motion_at(tau);
  predict(h);
  // The contact points depend on t1 only: the track's responses to the wheels are found once.
  evaluate_contacts(t1, x_, q_);
  unit_contact_responses();
  const double ca = newmark_.c_a(h), cv = newmark_.c_v(h);
  // Force scale [N] for the convergence test: the contact forces, and the inertial and
  // damping terms of the step, whose round-off bounds how small the residual can get.
  double force_scale = std::max(1.0, max_abs(rhs_t_));
  for (double f : contact_force_) force_scale = std::max(force_scale, std::abs(f));
  bool converged = false;
  int it = 0;
  for (; it < kMaxNewtonIterations && !converged; ++it) {
    newton_residuals(t1, it, ca, cv);
    // Converged when the residual forces are below 1e-10 of the force scale: the update they
    // would give is then far below any physical displacement (1e-10 x 1e5 N / 1e8 N/m).
    if (it > 0 && max_abs(r_t_) <= kRelativeTolerance * force_scale &&
        (vehicles_.dof_count() == 0 || max_abs(r_v_) <= kRelativeTolerance * force_scale)) {
      converged = true;
      break;
    }
    newton_update(it, ca, cv);
  }
  if (!converged) {
    std::ostringstream m;
    m << "track: Newton did not converge at t = " << t1 << " s in " << kMaxNewtonIterations
      << " iterations (contact loss and re-impact?); set a smaller track.integrator.micro_step";
    throw RunError(m.str());
  }
  last_iterations_ = it;
  correct(t1, h);
}

void TrackParticipant::footprint_motion_at(double tau) {
  const std::size_t n = structure_.sleeper_count();
  for (std::size_t i = 0; i < n; ++i) {  // Horner in tau
    double u = 0.0, v = 0.0;
    for (int k = static_cast<int>(input_.order); k >= 0; --k) {
      const std::size_t base = static_cast<std::size_t>(k) * 2 * n;
      u = u * tau + input_coeff_[base + i];
      v = v * tau + input_coeff_[base + n + i];
    }
    u_now_[i] = u;
    v_now_[i] = v;
  }
}

void TrackParticipant::predict(double h) {
  newmark_.predictors(h, x_, v_, a_, pa_t_, pv_t_);
  newmark_.predictors(h, q_, qd_, qdd_, pa_v_, pv_v_);
  structure_.mass().multiply(pa_t_.data(), rhs_t_.data());
  structure_.damping().multiply_add(1.0, pv_t_.data(), rhs_t_.data());
  if (soil_)
    soil_->predict(newmark_, h, pv_t_, rhs_t_.data());
  else
    ballast_load(rhs_t_.data());
  x_old_ = x_;
  q_old_ = q_;
  // Start from the constant-acceleration predictor.
  x_ += h * v_ + 0.5 * h * h * a_;
  q_ += h * qd_ + 0.5 * h * h * qdd_;
}

void TrackParticipant::unit_contact_responses() {
  // A^-1 N_w (the track half of Woodbury's D^-1 B) from the cached columns of A^-1 of the
  // contact point's four DOFs.
  const auto nt = x_.size();
  for (std::size_t w = 0; w < vehicles_.wheel_count(); ++w) {
    const auto wi = static_cast<Eigen::Index>(w);
    z_t_.col(wi).setZero();
    for (std::size_t k = 0; k < 4; ++k) {
      const double* column = inverse_columns_.column_by(contact_point_[w].dof[k],
                                                        [this](double* y) { solve_linear(y); });
      z_t_.col(wi) += contact_point_[w].shape[k] * Eigen::Map<const Eigen::VectorXd>(column, nt);
    }
  }
}

void TrackParticipant::newton_residuals(double t1, int it, double ca, double cv) {
  const std::size_t nw = vehicles_.wheel_count();
  vel_v_ = cv * q_ - pv_v_;
  acc_v_ = ca * q_ - pa_v_;
  evaluate_contacts(t1, x_, q_);
  // Residuals: r_t = A x - rhs - N F ; r_v = M(q) a - f + J^T F.
  if (it == 0) {
    a_track_operator_.multiply(x_.data(), r_t_.data());
    if (soil_) soil_->subtract_coupling(x_.data(), r_t_.data());
    r_t_ -= rhs_t_;
    for (std::size_t w = 0; w < nw; ++w)
      for (std::size_t k = 0; k < 4; ++k)
        r_t_[static_cast<Eigen::Index>(contact_point_[w].dof[k])] -=
            contact_point_[w].shape[k] * contact_force_[w];
  } else {
    // After a Newton update the linear track's residual lives on the contact DOFs only: the
    // update solved A y_t = r_t - N (F_lin - F), so r_t' = N (F_lin - F'), F_lin the contact
    // force the update predicted and F' the force now (exact up to the solve's round-off).
    r_t_.setZero();
    for (std::size_t w = 0; w < nw; ++w) {
      const auto wi = static_cast<Eigen::Index>(w);
      force_error_[wi] = contact_force_linear_[wi] - contact_force_[w];
      for (std::size_t k = 0; k < 4; ++k)
        r_t_[static_cast<Eigen::Index>(contact_point_[w].dof[k])] +=
            contact_point_[w].shape[k] * force_error_[wi];
    }
  }
  vehicles_.mass(q_, m_v_);
  vehicles_.forces(t1, q_, vel_v_, f_v_);
  vehicles_.tangent(t1, q_, vel_v_, k_v_, c_v_);
  r_v_.noalias() = m_v_ * acc_v_;
  r_v_ -= f_v_;
  for (std::size_t w = 0; w < nw; ++w)
    r_v_.noalias() += j_w_.row(static_cast<Eigen::Index>(w)).transpose() * contact_force_[w];
}

void TrackParticipant::newton_update(int it, double ca, double cv) {
  const std::size_t nw = vehicles_.wheel_count();
  a_vehicle_ = ca * m_v_ + cv * c_v_ + k_v_;
  lu_vehicle_.compute(a_vehicle_);
  // Woodbury: y = D^-1 r, Z = D^-1 B, S = I + K B^T Z, dx = y - Z S^-1 K B^T y.
  if (it == 0) {
    y_t_ = r_t_;
    solve_linear(y_t_.data());
  } else {
    y_t_.noalias() = z_t_ * force_error_;  // A^-1 N (F_lin - F'), no solve
  }
  y_v_ = lu_vehicle_.solve(r_v_);
  // All wheels at once into the whole of z_v_, then negated in place: a solve() negated, or
  // assigned to a column block, evaluates into a temporary (an allocation per Newton step).
  z_v_ = lu_vehicle_.solve(j_w_.transpose());
  z_v_ *= -1.0;
  for (std::size_t w = 0; w < nw; ++w) {
    const auto wi = static_cast<Eigen::Index>(w);
    const double kw = contact_stiffness_[w];
    for (std::size_t j = 0; j < nw; ++j) {
      const auto ji = static_cast<Eigen::Index>(j);
      const double btz = dot_rail(contact_point_[w], z_t_.col(ji)) - j_w_.row(wi).dot(z_v_.col(ji));
      s_small_(wi, ji) = (w == j ? 1.0 : 0.0) + kw * btz;
    }
    s_rhs_[wi] = kw * (dot_rail(contact_point_[w], y_t_) - j_w_.row(wi).dot(y_v_));
  }
  lu_small_.compute(s_small_);
  s_sol_ = lu_small_.solve(s_rhs_);
  y_t_.noalias() -= z_t_ * s_sol_;
  y_v_.noalias() -= z_v_ * s_sol_;
  x_ -= y_t_;
  q_ -= y_v_;
  // The contact forces this update predicts (delta changes by N^T y_t - J y_v).
  for (std::size_t w = 0; w < nw; ++w) {
    const auto wi = static_cast<Eigen::Index>(w);
    contact_force_linear_[wi] =
        contact_force_[w] +
        contact_stiffness_[w] * (dot_rail(contact_point_[w], y_t_) - j_w_.row(wi).dot(y_v_));
  }
}

void TrackParticipant::correct(double t1, double h) {
  newmark_.correct(h, x_old_, x_, v_, a_);
  newmark_.correct(h, q_old_, q_, qd_, qdd_);
  if (soil_) {
    soil_->correct(newmark_, h, x_);
    for (std::size_t i = 0; i < structure_.sleeper_count(); ++i) {
      u_now_[i] = soil_->soil().footprint_u(i);
      v_now_[i] = soil_->soil().footprint_v(i);
    }
  }
  evaluate_contacts(t1, x_, q_);  // forces consistent with the converged state, for outputs
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
