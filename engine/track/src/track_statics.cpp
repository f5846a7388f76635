// The track at rest under the vehicles' weight, iterated with the soil's statics to consistency:
// the wheel loads and vehicle DOFs by Newton on equilibrium and Hertz compatibility, the state the
// dynamics start from, and the micro-step the contact frequency allows. Apart from the dynamics
// because it runs once, with its own unknowns (the loads), before the first step.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "track/footprint_flexibility.hpp"
#include "track/hertz.hpp"
#include "track/static_interface.hpp"
#include "track/track_participant.hpp"
#include "track_participant_parts.hpp"

namespace rumble {
namespace {

// Micro-steps per period of the highest resolved resonance (wheel/rail contact, P1).
constexpr double kStepsPerContactPeriod = 20.0;

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

}  // namespace rumble
