// The lumped core (lumped_soil.hpp): parameters checked, Newmark sub-steps with a consistent
// start, exact receptance; docs/soils.md sections 6 and 7.
#include "lumped_soil.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace rumble::soils {
namespace {

/// Sub-steps per period of the fastest motion: Newmark's period error (w h)^2 / 12 is then 0.8 %
/// on the fastest mode, and much less on the band a track excites.
constexpr double kStepsPerCycle = 20.0;

}  // namespace

void LumpedSoil::accept_layout(const std::vector<Footprint>& footprints) {
  if (footprints.empty()) throw std::invalid_argument(type_ + ": the layout has no footprints");
  LumpedParameters p = parameters(footprints);
  check(p);
  n_ = static_cast<Eigen::Index>(footprints.size());
  p_ = std::move(p);
  any_massless_ = (p_.mass.array() == 0.0).any();
  all_massless_ = (p_.mass.array() == 0.0).all();

  for (Eigen::VectorXd* x : {&u_, &v_, &a_, &pa_, &pv_, &rhs_, &x_old_, &diag_, &off_})
    x->setZero(n_);
  off_.resize(std::max<Eigen::Index>(n_ - 1, 0));
  frf_diag_.resize(n_);
  frf_off_.resize(off_.size());
  frf_column_.resize(n_);
  for (TridiagonalLu<double>* lu : {&stiffness_lu_, &damping_lu_, &step_lu_}) lu->resize(n_);
  frf_lu_.resize(n_);

  // K is positive definite (k_i > 0); C is when every c_i > 0 (check() ensures it where a
  // massless coupled chain needs C^-1).
  assemble(1.0, 0.0, 0.0, diag_, off_);
  stiffness_lu_.factor(diag_, off_);
  if (all_massless_ && coupled() && p_.damping[0] > 0.0) {
    assemble(0.0, 1.0, 0.0, diag_, off_);
    damping_lu_.factor(diag_, off_);
  }
  factored_step_ = -1.0;
  sub_step_ = max_step_ > 0.0 ? max_step_ : automatic_sub_step();
}

void LumpedSoil::check(const LumpedParameters& p) const {
  const auto n = p.stiffness.size();
  std::ostringstream m;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double k = p.stiffness[i], c = p.damping[i], mass = p.mass[i];
    if (!(k > 0.0 && c >= 0.0 && mass >= 0.0) || !std::isfinite(k + c + mass)) {
      m << type_ << ": footprint " << i << " gets k = " << k << " N/m, c = " << c
        << " N s/m, m = " << mass << " kg; need k > 0, c >= 0, m >= 0";
      throw std::invalid_argument(m.str());
    }
  }
  if (!(p.coupling_stiffness >= 0.0 && p.coupling_damping >= 0.0) ||
      !std::isfinite(p.coupling_stiffness + p.coupling_damping)) {
    m << type_ << ": coupling spring " << p.coupling_stiffness << " N/m and dashpot "
      << p.coupling_damping << " N s/m must be >= 0";
    throw std::invalid_argument(m.str());
  }
  if (p.coupling_stiffness == 0.0 && p.coupling_damping == 0.0) return;
  // Coupled footprints: the consistent start (docs/soils.md) needs either masses everywhere, or
  // none and a non-singular C (every c_i > 0), or none and no dashpot at all (quasi-static).
  for (Eigen::Index i = 1; i < n; ++i) {
    if ((p.mass[i] == 0.0) != (p.mass[0] == 0.0)) {
      m << type_ << ": coupled footprints must all have a mass or all have none; footprint " << i
        << " has m = " << p.mass[i] << " kg, footprint 0 has " << p.mass[0] << " kg";
      throw std::invalid_argument(m.str());
    }
  }
  if (p.mass[0] > 0.0) return;
  const bool all_damped = (p.damping.array() > 0.0).all();
  const bool undamped = (p.damping.array() == 0.0).all() && p.coupling_damping == 0.0;
  if (!all_damped && !undamped) {
    m << type_ << ": massless coupled footprints need a dashpot to the ground at every footprint "
      << "(c > 0), or no dashpot at all; got c = " << p.damping.minCoeff()
      << " N s/m and a coupling dashpot of " << p.coupling_damping
      << " N s/m (give a mass, a ground dashpot, or drop the coupling dashpot)";
    throw std::invalid_argument(m.str());
  }
}

double LumpedSoil::automatic_sub_step() const {
  // Bounds on the fastest rate [1/s] of the free motion (Gershgorin's theorem on M^-1 K and
  // M^-1 C, row sums k_i + 4 k_c and c_i + 4 c_c; for massless rows the largest eigenvalue of
  // C^-1 K, bounded by the Rayleigh quotient, docs/soils.md "Sub-step").
  const double kc = p_.coupling_stiffness, cc = p_.coupling_damping;
  double rate = 0.0, ratio = 0.0, c_min = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < n_; ++i) {
    const double m = p_.mass[i], k = p_.stiffness[i], c = p_.damping[i];
    if (m > 0.0) {
      rate = std::max({rate, std::sqrt((k + 4.0 * kc) / m), (c + 4.0 * cc) / m});
    } else if (c > 0.0) {
      ratio = std::max(ratio, k / c);
      c_min = std::min(c_min, c);
    }
  }
  if (ratio > 0.0) rate = std::max({rate, ratio, (ratio * c_min + 4.0 * kc) / (c_min + 4.0 * cc)});
  return rate > 0.0 ? 2.0 * std::numbers::pi / (kStepsPerCycle * rate)
                    : std::numeric_limits<double>::infinity();
}

template <class T>
void LumpedSoil::assemble(T wk, T wc, T wm, Eigen::Matrix<T, Eigen::Dynamic, 1>& diag,
                          Eigen::Matrix<T, Eigen::Dynamic, 1>& off) const {
  const double kc = p_.coupling_stiffness, cc = p_.coupling_damping;
  for (Eigen::Index i = 0; i < n_; ++i) {
    diag[i] = wk * (p_.stiffness[i] + neighbours(i) * kc) +
              wc * (p_.damping[i] + neighbours(i) * cc) + wm * p_.mass[i];
  }
  for (Eigen::Index i = 0; i + 1 < n_; ++i) off[i] = -(wk * kc + wc * cc);
}

void LumpedSoil::linear_matrix(rumble_matrix which, CscMatrix& out) {
  require_layout("linear_matrix");
  switch (which) {
    case RUMBLE_MATRIX_MASS:
      return chain_csc(p_.mass, 0.0, out);
    case RUMBLE_MATRIX_DAMPING:
      return chain_csc(p_.damping, p_.coupling_damping, out);
    case RUMBLE_MATRIX_STIFFNESS:
      return chain_csc(p_.stiffness, p_.coupling_stiffness, out);
    case RUMBLE_MATRIX_INPUT:
      return chain_csc(Eigen::VectorXd::Ones(n_), 0.0, out);
  }
  throw std::invalid_argument(type_ + ": linear_matrix: no matrix number " +
                              std::to_string(static_cast<int>(which)) + " (0..3: M, C, K, B)");
}

void LumpedSoil::chain_csc(const Eigen::VectorXd& diagonal, double coupling, CscMatrix& out) const {
  out.rows = out.cols = static_cast<std::uint64_t>(n_);
  out.col_ptr.assign(1, 0);
  out.row_index.clear();
  out.values.clear();
  const auto add = [&](Eigen::Index row, double value) {
    if (value == 0.0) return;
    out.row_index.push_back(row);
    out.values.push_back(value);
  };
  for (Eigen::Index j = 0; j < n_; ++j) {  // column j: rows j-1, j, j+1 (sorted)
    if (j > 0) add(j - 1, -coupling);
    add(j, diagonal[j] + neighbours(j) * coupling);
    if (j + 1 < n_) add(j + 1, -coupling);
    out.col_ptr.push_back(static_cast<std::int64_t>(out.values.size()));
  }
}

double LumpedSoil::chain_row(const Eigen::VectorXd& diagonal, double coupling,
                             const Eigen::VectorXd& x, Eigen::Index i) const {
  double s = (diagonal[i] + neighbours(i) * coupling) * x[i];
  if (i > 0) s -= coupling * x[i - 1];
  if (i + 1 < n_) s -= coupling * x[i + 1];
  return s;
}

void LumpedSoil::consistent_start(const Waveform& force, double H) {
  // The waveform may jump at t (a coupler's new prediction, a held value): the state then
  // satisfies M a + C v + K u = F(t+) with u continuous, and v continuous where there is mass.
  // Massless footprints: v from C v = F - K u (trapezoidal rule without ringing), or, with no
  // dashpot, u = K^-1 F and v = K^-1 dF/dt (a quasi-static spring). Massive footprints: a from
  // the equation. (Massive rows never read u or v of massless ones: check() keeps them apart.)
  const auto slope = [&](Eigen::Index i) {  // dF_i/dt at tau = 0, exact for order <= 2
    const auto j = static_cast<std::size_t>(i);
    return (-3.0 * force.at(j, 0.0) + 4.0 * force.at(j, 0.5) - force.at(j, 1.0)) / H;
  };
  for (Eigen::Index i = 0; i < n_; ++i)
    rhs_[i] = force.at(static_cast<std::size_t>(i), 0.0) -
              chain_row(p_.stiffness, p_.coupling_stiffness, u_, i);
  if (any_massless_ && coupled()) {  // then every footprint is massless (check())
    if (p_.damping[0] > 0.0) {
      v_ = rhs_;
      damping_lu_.solve(v_);
    } else {  // no inertia, no dashpot: u = K^-1 F and v = K^-1 F' follow the force at once
      for (Eigen::Index i = 0; i < n_; ++i) {
        u_[i] = force.at(static_cast<std::size_t>(i), 0.0);
        v_[i] = slope(i);
      }
      stiffness_lu_.solve(u_);
      stiffness_lu_.solve(v_);
    }
  } else if (any_massless_) {
    for (Eigen::Index i = 0; i < n_; ++i) {
      if (p_.mass[i] > 0.0) continue;
      if (p_.damping[i] > 0.0) {
        v_[i] = rhs_[i] / p_.damping[i];
      } else {
        u_[i] = force.at(static_cast<std::size_t>(i), 0.0) / p_.stiffness[i];
        v_[i] = slope(i) / p_.stiffness[i];
      }
    }
  }
  for (Eigen::Index i = 0; i < n_; ++i) {
    a_[i] = p_.mass[i] > 0.0
                ? (rhs_[i] - chain_row(p_.damping, p_.coupling_damping, v_, i)) / p_.mass[i]
                : 0.0;
  }
}

void LumpedSoil::require_layout(const char* call) const {
  if (n_ == 0) throw std::logic_error(type_ + ": " + call + " called before accept_layout");
}

void LumpedSoil::initialize(double /*t0*/, const double* static_force, double* static_u) {
  require_layout("initialize");
  for (Eigen::Index i = 0; i < n_; ++i) {
    if (!std::isfinite(static_force[i])) {
      std::ostringstream m;
      m << type_ << ": static force at footprint " << i << " is " << static_force[i];
      throw std::invalid_argument(m.str());
    }
  }
  u_ = Eigen::Map<const Eigen::VectorXd>(static_force, n_);
  stiffness_lu_.solve(u_);  // K u = F
  v_.setZero();
  Eigen::Map<Eigen::VectorXd>(static_u, n_) = u_;
}

void LumpedSoil::advance(double /*t*/, double H, const Waveform& force) {
  require_layout("advance");
  const bool bad_step = !(H > 0.0) || !std::isfinite(H);
  if (bad_step || force.channels() != static_cast<std::size_t>(n_) || H / sub_step_ > 1e9) {
    std::ostringstream m;  // only on refusal: advance() allocates nothing otherwise
    m << type_ << ": ";
    if (bad_step) {
      m << "macro step H must be > 0 s, got " << H;
    } else if (force.channels() != static_cast<std::size_t>(n_)) {
      m << "the force waveform has " << force.channels() << " channels, expected " << n_
        << " (one per footprint)";
    } else {
      m << "macro step " << H << " s needs more than 1e9 sub-steps of " << sub_step_ << " s";
    }
    throw std::invalid_argument(m.str());
  }

  // Equal sub-steps no longer than sub_step_ (the 1e-12 keeps H = 3 sub_step_ at 3 steps).
  const auto steps = std::max(1.0, std::ceil(H / sub_step_ * (1.0 - 1e-12)));
  const double h = H / steps;
  if (h != factored_step_) {
    assemble(1.0, newmark_.c_v(h), newmark_.c_a(h), diag_, off_);
    step_lu_.factor(diag_, off_);  // K + c_v C + c_a M: positive definite
    factored_step_ = h;
  }
  consistent_start(force, H);
  for (double s = 1.0; s <= steps; s += 1.0) {
    const double tau = s / steps;
    newmark_.predictors(h, u_, v_, a_, pa_, pv_);
    for (Eigen::Index i = 0; i < n_; ++i)
      rhs_[i] = force.at(static_cast<std::size_t>(i), tau) + p_.mass[i] * pa_[i] +
                chain_row(p_.damping, p_.coupling_damping, pv_, i);
    x_old_ = u_;
    u_ = rhs_;
    step_lu_.solve(u_);
    newmark_.correct(h, x_old_, u_, v_, a_);
  }
}

void LumpedSoil::motion(double* u, double* v) const {
  Eigen::Map<Eigen::VectorXd>(u, n_) = u_;
  Eigen::Map<Eigen::VectorXd>(v, n_) = v_;
}

bool LumpedSoil::frequency_response(double f_hz, std::complex<double>* receptance) {
  require_layout("frequency_response");
  if (!std::isfinite(f_hz))
    throw std::invalid_argument(type_ + ": frequency must be finite, got " + std::to_string(f_hz));
  const double w = 2.0 * std::numbers::pi * f_hz;
  using C = std::complex<double>;
  assemble(C(1.0), C(0.0, w), C(-w * w), frf_diag_, frf_off_);
  if (!frf_lu_.factor(frf_diag_, frf_off_)) {
    std::ostringstream m;
    m << type_ << ": the dynamic stiffness is singular at f = " << f_hz
      << " Hz (an undamped resonance)";
    throw std::invalid_argument(m.str());
  }
  for (Eigen::Index j = 0; j < n_; ++j) {  // column j: the response to a unit force at j
    frf_column_.setZero();
    frf_column_[j] = 1.0;
    frf_lu_.solve(frf_column_, j);
    Eigen::Map<VectorXcd>(receptance + j * n_, n_) = frf_column_;
  }
  return true;
}

void LumpedSoil::save_state(double* buffer) const {
  for (const Eigen::VectorXd* x : {&u_, &v_}) {
    Eigen::Map<Eigen::VectorXd>(buffer, n_) = *x;
    buffer += n_;
  }
}

void LumpedSoil::restore_state(const double* buffer) {
  for (Eigen::VectorXd* x : {&u_, &v_}) {
    *x = Eigen::Map<const Eigen::VectorXd>(buffer, n_);
    buffer += n_;
  }
}

}  // namespace rumble::soils
