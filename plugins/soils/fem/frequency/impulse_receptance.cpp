#include "frequency/impulse_receptance.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace rumble::fem {

ImpulseReceptance::ImpulseReceptance(const ExplicitSolver& op, const FootprintWeights& weights,
                                     double dt, double duration, double f_top,
                                     const std::function<void(std::size_t, std::size_t)>& progress,
                                     const StaticFarField* far, double tau)
    : n_(weights.size()), dt_(dt), f_top_(3.0 * f_top) {
  const std::size_t steps = static_cast<std::size_t>(std::ceil(duration / dt));
  const double pulse = 0.5 / f_top;  // s: a Hann pulse's spectrum is half its peak at 1 / length
  force_.resize(steps);
  for (std::size_t k = 0; k < steps; ++k) {
    const double t = static_cast<double>(k + 1) * dt;
    force_[k] = t < pulse ? 0.5 * (1.0 - std::cos(2.0 * std::numbers::pi * t / pulse)) : 0.0;
  }
  motion_.assign(n_ * n_ * steps, 0.0);
  const Eigen::Index dofs = op.dofs();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(dofs);
  const std::size_t tail = steps - steps / 10;
  double peak = 0.0, late = 0.0;
  const double keep = far != nullptr ? std::exp(-dt / tau) : 0.0;  // the lag over a step
  for (std::size_t j = 0; j < n_; ++j) {
    ExplicitState s = op.rest_state();
    double lagged = 0.0;  // [N] the force the far field follows
    for (std::size_t k = 0; k < steps; ++k) {
      if (k % 64 == 0) progress(j, k);
      for (const NodalWeight& w : weights[j]) f[3 * w.node + 2] = w.weight * force_[k];
      if (far != nullptr) {
        lagged = force_[k] + (lagged - force_[k]) * keep;
        far->set_column(j, lagged, f);
      }
      op.step(s, f, dt);
      for (std::size_t i = 0; i < n_; ++i) {
        const double u = footprint_average(weights[i], s.w.data());
        motion_[(j * n_ + i) * steps + k] = u;
        peak = std::max(peak, std::abs(u));
        if (k >= tail) late = std::max(late, std::abs(u));
      }
    }
  }
  decay_ratio_ = peak > 0.0 ? late / peak : 0.0;
}

void ImpulseReceptance::at(double f_hz, std::complex<double>* H) const {
  const std::size_t steps = force_.size();
  const double w = 2.0 * std::numbers::pi * f_hz;
  std::vector<std::complex<double>> phase(steps);  // e^{-i w t_k}
  std::complex<double> F = 0.0;
  double F0 = 0.0;
  for (std::size_t k = 0; k < steps; ++k) {
    phase[k] = std::polar(1.0, -w * static_cast<double>(k + 1) * dt_);
    F += force_[k] * phase[k];
    F0 += force_[k];
  }
  if (!(std::abs(F) > 1e-3 * F0)) {
    std::ostringstream m;
    m << "fem: the receptance at " << f_hz << " Hz is beyond the impulse responses' band (their "
      << "pulse has no energy there; it covers up to about " << f_top_ << " Hz): ask for lower "
      << "frequencies, raise params/mesh/f_max, or use params/receptance/method \"lu\"";
    throw std::invalid_argument(m.str());
  }
  for (std::size_t j = 0; j < n_; ++j)
    for (std::size_t i = 0; i < n_; ++i) {
      const double* u = motion_.data() + (j * n_ + i) * steps;
      std::complex<double> U = 0.0;
      for (std::size_t k = 0; k < steps; ++k) U += u[k] * phase[k];
      H[i + n_ * j] = U / F;
    }
}

}  // namespace rumble::fem
