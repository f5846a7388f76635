// The track's dynamics: a macro step in micro-steps, each a Newmark step with a Newton iteration on
// the Hertz contacts solved by the Woodbury identity (track/track_participant.hpp). The hot path
// of a run, kept in one file so that its steps and their work space read together.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "core/errors.hpp"
#include "track/track_participant.hpp"
#include "track_participant_parts.hpp"

namespace rumble {

void TrackParticipant::ballast_load(double* f) const {
  const TrackConfig& c = structure_.config();
  for (std::size_t i = 0; i < structure_.sleeper_count(); ++i)
    f[structure_.sleeper_dof(i)] += c.ballast_k * u_now_[i] + c.ballast_c * v_now_[i];
}

void TrackParticipant::solve_linear(double* y) const {
  a_track_.solve(y);
  if (soil_) soil_->correct_solve(y);
}

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

}  // namespace rumble
