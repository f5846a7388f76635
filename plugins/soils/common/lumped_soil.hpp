// The machinery shared by the reduced soils (winkler, clm): per footprint i a mass m_i on a
// spring k_i and dashpot c_i to the fixed ground, and between neighbours i, i+1 a spring k_c
// and a dashpot c_c (zero for Winkler):
//   M u'' + C u' + K u = F,  M = diag(m),  K, C tridiagonal,  u, F down + (abi.h convention).
// Time integration: Newmark average acceleration (rumble/newmark.hpp) in sub-steps of at most
// max_step inside each macro step, the force waveform evaluated at every sub-step; with m = 0
// it reduces to the trapezoidal rule for C u' + K u = F. The effective matrix is tridiagonal,
// factored once per sub-step size (LDL^T), so a sub-step costs O(n) and allocates nothing.
// Frequency response: H(f) = (K - w^2 M + i w C)^-1, exact (dense complex LU).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <rumble/newmark.hpp>
#include <rumble/plugin.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace rumble::soils {

class LumpedSoil : public rumble::Soil {
 public:
  void accept_layout(const std::vector<Footprint>& footprints) override {
    n_ = footprints.size();
    if (n_ == 0) throw std::invalid_argument(std::string(name()) + ": no footprints");
    m_.assign(n_, 0.0);
    k_.assign(n_, 0.0);
    c_.assign(n_, 0.0);
    configure(footprints);  // the model fills m_, k_, c_, k_coupling_, c_coupling_
    for (std::size_t i = 0; i < n_; ++i) {
      if (!(k_[i] > 0.0) || !(c_[i] >= 0.0) || !(m_[i] >= 0.0)) {
        throw std::invalid_argument(
            std::string(name()) + ": footprint " + std::to_string(i) +
            " got k = " + std::to_string(k_[i]) + " N/m, c = " + std::to_string(c_[i]) +
            " N s/m, m = " + std::to_string(m_[i]) + " kg; need k > 0, c >= 0, m >= 0");
      }
    }
    for (auto* v : {&u_, &v_, &a_, &pa_, &pv_, &rhs_, &x_old_, &diag_, &lower_}) v->assign(n_, 0.0);
    h_factored_ = -1.0;
    if (max_step_ <= 0.0) max_step_ = default_max_step();
  }

  void initialize(double /*t0*/, const double* static_force, double* static_u) override {
    require_layout();
    // K u = F: factor K alone (c_a = c_v = 0) and solve.
    factor(0.0, 0.0);
    std::copy(static_force, static_force + n_, u_.begin());
    solve(u_);
    std::copy(u_.begin(), u_.end(), static_u);
    std::fill(v_.begin(), v_.end(), 0.0);
    std::fill(a_.begin(), a_.end(), 0.0);
    h_factored_ = -1.0;
  }

  void advance(double /*t*/, double H, const Waveform& force) override {
    require_layout();
    if (force.channels() != n_) {
      throw std::invalid_argument(std::string(name()) + ": force waveform has " +
                                  std::to_string(force.channels()) + " channels, expected " +
                                  std::to_string(n_));
    }
    const int steps = std::max(1, static_cast<int>(std::ceil(H / max_step_ - 1e-9)));
    const double h = H / steps;
    if (h != h_factored_) {
      factor(newmark_.c_a(h), newmark_.c_v(h));
      h_factored_ = h;
    }
    for (int s = 1; s <= steps; ++s) {
      const double tau = static_cast<double>(s) / steps;
      newmark_.predictors(h, u_, v_, a_, pa_, pv_);
      for (std::size_t i = 0; i < n_; ++i) rhs_[i] = force.at(i, tau) + m_[i] * pa_[i];
      multiply_add_damping(pv_, rhs_);
      x_old_ = u_;
      u_ = rhs_;
      solve(u_);
      newmark_.correct(h, x_old_, u_, v_, a_);
    }
  }

  void motion(double* u, double* v) const override {
    std::copy(u_.begin(), u_.end(), u);
    std::copy(v_.begin(), v_.end(), v);
  }

  bool frequency_response(double f_hz, std::complex<double>* receptance) override {
    require_layout();
    const double w = 2.0 * std::numbers::pi * f_hz;
    const auto n = static_cast<Eigen::Index>(n_);
    Eigen::MatrixXcd dyn = Eigen::MatrixXcd::Zero(n, n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto s = static_cast<std::size_t>(i);
      dyn(i, i) = {k_[s] + neighbours(s) * k_coupling_ - w * w * m_[s],
                   w * (c_[s] + neighbours(s) * c_coupling_)};
      if (i + 1 < n) dyn(i, i + 1) = dyn(i + 1, i) = {-k_coupling_, -w * c_coupling_};
    }
    const Eigen::MatrixXcd h = dyn.partialPivLu().inverse();
    std::copy(h.data(), h.data() + n * n, receptance);  // column-major
    return true;
  }

  std::size_t state_size() const override { return 3 * n_; }
  void save_state(double* b) const override {
    for (const auto* v : {&u_, &v_, &a_}) b = std::copy(v->begin(), v->end(), b);
  }
  void restore_state(const double* b) override {
    for (auto* v : {&u_, &v_, &a_}) {
      std::copy(b, b + n_, v->begin());
      b += n_;
    }
  }

  // For tests and docs: the lumped parameters in force.
  double mass(std::size_t i) const { return m_[i]; }
  double stiffness(std::size_t i) const { return k_[i]; }
  double damping(std::size_t i) const { return c_[i]; }
  double coupling_stiffness() const { return k_coupling_; }
  double coupling_damping() const { return c_coupling_; }
  double max_step() const { return max_step_; }

 protected:
  /// Type name for messages.
  virtual const char* name() const = 0;
  /// Sets m_, k_, c_ (sized n) and k_coupling_, c_coupling_ for this layout.
  virtual void configure(const std::vector<Footprint>& footprints) = 0;

  std::vector<double> m_, k_, c_;  // kg, N/m, N s/m per footprint
  double k_coupling_ = 0.0;        // N/m between neighbours
  double c_coupling_ = 0.0;        // N s/m between neighbours
  double max_step_ = 0.0;          // s; 0 = choose in accept_layout
  std::size_t n_ = 0;

 private:
  double neighbours(std::size_t i) const { return (i > 0 ? 1.0 : 0.0) + (i + 1 < n_ ? 1.0 : 0.0); }

  void require_layout() const {
    if (n_ == 0) throw std::logic_error(std::string(name()) + ": used before accept_layout");
  }

  /// Sub-step: 1/20 of the shortest natural period when there is mass; otherwise 1/10 of the
  /// shortest relaxation time c/k, so the trapezoidal rule resolves the decay.
  double default_max_step() const {
    double h = 1e-3;  // s, upper bound
    for (std::size_t i = 0; i < n_; ++i) {
      const double k = k_[i] + 4.0 * k_coupling_, c = c_[i] + 4.0 * c_coupling_;
      if (m_[i] > 0.0)
        h = std::min(h, 2.0 * std::numbers::pi * std::sqrt(m_[i] / k) / 20.0);
      else if (c > 0.0)
        h = std::min(h, 0.1 * c / k);
    }
    return h;
  }

  /// LDL^T of the tridiagonal A = K + cv C + ca M (diag_: D, lower_: L's sub-diagonal).
  void factor(double ca, double cv) {
    const double off = -k_coupling_ - cv * c_coupling_;
    for (std::size_t i = 0; i < n_; ++i) {
      const double a_ii = k_[i] + neighbours(i) * k_coupling_ +
                          cv * (c_[i] + neighbours(i) * c_coupling_) + ca * m_[i];
      diag_[i] = i == 0 ? a_ii : a_ii - lower_[i - 1] * lower_[i - 1] * diag_[i - 1];
      if (!(diag_[i] > 0.0))
        throw std::runtime_error(std::string(name()) + ": matrix not positive definite");
      if (i + 1 < n_) lower_[i] = off / diag_[i];
    }
  }

  void solve(std::vector<double>& x) const {
    for (std::size_t i = 1; i < n_; ++i) x[i] -= lower_[i - 1] * x[i - 1];
    for (std::size_t i = 0; i < n_; ++i) x[i] /= diag_[i];
    for (std::size_t i = n_ - 1; i-- > 0;) x[i] -= lower_[i] * x[i + 1];
  }

  /// y += C x.
  void multiply_add_damping(const std::vector<double>& x, std::vector<double>& y) const {
    for (std::size_t i = 0; i < n_; ++i) {
      double s = (c_[i] + neighbours(i) * c_coupling_) * x[i];
      if (i > 0) s -= c_coupling_ * x[i - 1];
      if (i + 1 < n_) s -= c_coupling_ * x[i + 1];
      y[i] += s;
    }
  }

  Newmark newmark_;
  std::vector<double> u_, v_, a_, pa_, pv_, rhs_, x_old_, diag_, lower_;
  double h_factored_ = -1.0;
};

}  // namespace rumble::soils
