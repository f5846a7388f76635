// Fixed-point accelerators of the implicit coupler (plugin-internal; unit-tested directly by
// tests/couplers). They work on the vector x the soil takes as its end-of-step input: the track's
// outputs at the end of the macro step, i.e. the footprint forces F [N] (n channels).
//
// One macro step is the fixed point x = G(x), G = "the soil advances under x, then the track
// advances under the soil's new motion and returns its forces". Iteration k evaluates
// x~_k = G(x_k) and the residual r_k = x~_k - x_k [N]; the accelerator returns x_{k+1}:
//
//   constant   x_{k+1} = x_k + w r_k, w [-] fixed.
//   aitken     dynamic relaxation (Irons-Tuck form, Kuettler & Wall 2008):
//                w_k = -w_{k-1} r_{k-1}^T (r_k - r_{k-1}) / |r_k - r_{k-1}|^2   (r^T r in N^2)
//              and x_{k+1} = x_k + w_k r_k. The first iteration of a step takes
//              w_0 = sign(w_prev) min(w_init, |w_prev|), w_prev the last factor of the previous
//              step (preCICE's convention).
//   iqn_ils    interface quasi-Newton, inverse Jacobian from a least-squares fit (Degroote,
//              Bathe & Vierendeels 2009; preCICE's IQN-ILS). Columns, newest first, from
//              consecutive iterates of this step and of the last q accepted steps:
//                V = [r_{i+1} - r_i ...]    [N]   residual differences
//                W = [x~_{i+1} - x~_i ...]  [N]   differences of G's outputs
//              alpha [-] minimises |V alpha + r_k| (economy QR of V by modified Gram-Schmidt),
//              and x_{k+1} = x~_k + W alpha (so that the residual predicted by the secant model
//              is zero). QR2 filter: a column whose part orthogonal to the newer kept columns is
//              less than epsilon of its own norm is left out of that solve (nearly dependent
//              columns make R ill-conditioned). With no columns (the first iteration of a run,
//              or of a step without reuse) it relaxes with w_init.
//              Columns of reused steps are dropped when the step length changes (G depends on
//              it): lazily, at the first update of a step with another length, so that an
//              attempt refused before any update (DISCARD, retried as halves) leaves no trace.
//
// Storage is sized once (n x max_columns per matrix): no allocation per step or iteration.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace rumble_implicit {

enum class Method { kConstant, kAitken, kIqnIls };

/// "constant", "aitken", "iqn_ils" (the schema's enum); throws for anything else.
inline Method method_from_name(const std::string& name) {
  if (name == "constant") return Method::kConstant;
  if (name == "aitken") return Method::kAitken;
  if (name == "iqn_ils") return Method::kIqnIls;
  throw std::invalid_argument("params/acceleration: unknown method '" + name +
                              "'; one of constant, aitken, iqn_ils");
}

struct AccelerationSettings {
  Method method = Method::kIqnIls;
  double omega = 0.5;             // [-] constant factor; initial factor of aitken and iqn_ils
  std::size_t reused_steps = 8;   // q: accepted steps whose columns iqn_ils keeps
  std::size_t max_columns = 100;  // columns iqn_ils keeps at most (oldest dropped)
  double filter_epsilon = 1e-2;   // [-] QR2 filter threshold
};

class Accelerator {
 public:
  Accelerator(const AccelerationSettings& s, std::size_t n)
      : s_(s),
        n_(n),
        cap_(s.method == Method::kIqnIls ? std::max<std::size_t>(s.max_columns, 1) : 0),
        omega_(s.omega),
        r_(n),
        r_prev_(n),
        xt_prev_(n),
        v_(cap_ * n),
        w_(cap_ * n),
        q_(cap_ * n),
        r_mat_(cap_ * cap_),
        rhs_(cap_),
        alpha_(cap_),
        kept_(cap_),
        col_step_(cap_) {
    if (!(s.omega > 0.0)) throw std::invalid_argument("acceleration: omega must be > 0");
  }

  /// A macro step of length h [s] begins (or is taken again after a refusal): this step's
  /// iterates so far are forgotten.
  void begin_step(double h) {
    while (count_ > 0 && col_step_[slot(0)] == step_) drop_newest();
    iteration_ = 0;
    h_ = h;
  }

  /// Iteration of this step: x was the input [N], x_tilde = G(x) [N]; writes the next input.
  void next(const std::vector<double>& x, const std::vector<double>& x_tilde,
            std::vector<double>& x_next) {
    x_next.resize(n_);
    for (std::size_t i = 0; i < n_; ++i) r_[i] = x_tilde[i] - x[i];
    switch (s_.method) {
      case Method::kConstant:
        omega_ = s_.omega;
        relax(x, omega_, x_next);
        break;
      case Method::kAitken:
        aitken(x, x_next);
        break;
      case Method::kIqnIls:
        quasi_newton(x, x_tilde, x_next);
        break;
    }
    std::copy(r_.begin(), r_.end(), r_prev_.begin());
    std::copy(x_tilde.begin(), x_tilde.end(), xt_prev_.begin());
    ++iteration_;
  }

  /// The step was accepted: iqn_ils keeps the columns of the last q accepted steps, this one's
  /// included (q = 0: none is reused).
  void end_step() {
    if (count_ > 0 && col_step_[slot(0)] == step_) stored_h_ = h_;
    ++step_;
    while (count_ > 0 && col_step_[slot(count_ - 1)] + s_.reused_steps < step_) --count_;
    iteration_ = 0;
  }

  double omega() const { return omega_; }             // [-] last relaxation factor
  std::size_t columns() const { return count_; }      // iqn_ils columns stored
  std::size_t columns_used() const { return used_; }  // ... kept by the last solve's filter

 private:
  void relax(const std::vector<double>& x, double omega, std::vector<double>& x_next) const {
    for (std::size_t i = 0; i < n_; ++i) x_next[i] = x[i] + omega * r_[i];
  }

  void aitken(const std::vector<double>& x, std::vector<double>& x_next) {
    if (iteration_ == 0) {
      omega_ = std::copysign(std::min(s_.omega, std::abs(omega_)), omega_);
    } else {
      double num = 0.0, den = 0.0;  // N^2
      for (std::size_t i = 0; i < n_; ++i) {
        const double dr = r_[i] - r_prev_[i];
        num += r_prev_[i] * dr;
        den += dr * dr;
      }
      if (den > 0.0) omega_ = -omega_ * num / den;
    }
    relax(x, omega_, x_next);
  }

  /// Storage slot of the column `age` columns back from the newest (0: newest).
  std::size_t slot(std::size_t age) const { return (head_ + cap_ - age) % cap_; }
  void drop_newest() {
    head_ = (head_ + cap_ - 1) % cap_;
    --count_;
  }

  void quasi_newton(const std::vector<double>& x, const std::vector<double>& x_tilde,
                    std::vector<double>& x_next) {
    if (iteration_ == 0 && count_ > 0 && h_ != stored_h_) count_ = 0;  // G depends on h
    if (iteration_ > 0) {          // a new column pair from this step's last two iterates
      head_ = (head_ + 1) % cap_;  // when full, this overwrites the oldest column
      count_ = std::min(count_ + 1, cap_);
      col_step_[head_] = step_;
      double* v = &v_[head_ * n_];
      double* w = &w_[head_ * n_];
      for (std::size_t i = 0; i < n_; ++i) {
        v[i] = r_[i] - r_prev_[i];
        w[i] = x_tilde[i] - xt_prev_[i];
      }
    }
    used_ = factorize();
    if (used_ == 0) {
      omega_ = s_.omega;
      relax(x, omega_, x_next);
      return;
    }
    // alpha = R^-1 Q^T (-r): back substitution over the kept columns.
    for (std::size_t a = 0; a < used_; ++a) {
      const double* q = &q_[a * n_];
      double dot = 0.0;
      for (std::size_t i = 0; i < n_; ++i) dot += q[i] * r_[i];
      rhs_[a] = -dot;
    }
    for (std::size_t a = used_; a-- > 0;) {
      double sum = rhs_[a];
      for (std::size_t b = a + 1; b < used_; ++b) sum -= r_mat_[a * cap_ + b] * alpha_[b];
      alpha_[a] = sum / r_mat_[a * cap_ + a];
    }
    std::copy(x_tilde.begin(), x_tilde.end(), x_next.begin());
    for (std::size_t a = 0; a < used_; ++a) {
      const double* w = &w_[slot(kept_[a]) * n_];
      for (std::size_t i = 0; i < n_; ++i) x_next[i] += alpha_[a] * w[i];
    }
  }

  /// Modified Gram-Schmidt QR of V (newest column first) with the QR2 filter: q_ holds the kept
  /// columns orthonormalised, r_mat_ the upper triangle (stride cap_), kept_ their ages.
  /// Returns how many were kept.
  std::size_t factorize() {
    std::size_t m = 0;
    for (std::size_t age = 0; age < count_; ++age) {
      double* q = &q_[m * n_];
      const double* v = &v_[slot(age) * n_];
      std::copy(v, v + n_, q);
      const double norm0 = norm(q);
      for (std::size_t a = 0; a < m; ++a) {
        const double* qa = &q_[a * n_];
        double dot = 0.0;
        for (std::size_t i = 0; i < n_; ++i) dot += qa[i] * q[i];
        r_mat_[a * cap_ + m] = dot;
        for (std::size_t i = 0; i < n_; ++i) q[i] -= dot * qa[i];
      }
      const double rest = norm(q);
      if (!(norm0 > 0.0) || !(rest >= s_.filter_epsilon * norm0)) continue;  // nearly dependent
      for (std::size_t i = 0; i < n_; ++i) q[i] /= rest;
      r_mat_[m * cap_ + m] = rest;
      kept_[m] = age;
      ++m;
    }
    return m;
  }

  double norm(const double* a) const {
    double s = 0.0;
    for (std::size_t i = 0; i < n_; ++i) s += a[i] * a[i];
    return std::sqrt(s);
  }

  AccelerationSettings s_;
  std::size_t n_, cap_;
  double omega_;                              // [-]
  double h_ = 0.0, stored_h_ = 0.0;           // [s] this step's length; the reused columns'
  std::size_t iteration_ = 0;                 // updates in this step so far
  std::uint64_t step_ = 0;                    // accepted steps so far (the current step's id)
  std::vector<double> r_, r_prev_, xt_prev_;  // [N]
  std::vector<double> v_, w_;                 // [N] column rings, n x cap_ each
  std::vector<double> q_, r_mat_, rhs_, alpha_;
  std::vector<std::size_t> kept_;
  std::vector<std::uint64_t> col_step_;  // accepted-step id of each stored column
  std::size_t head_ = 0, count_ = 0, used_ = 0;
};

}  // namespace rumble_implicit
