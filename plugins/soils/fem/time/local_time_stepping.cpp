#include "time/local_time_stepping.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace rumble::fem {

namespace {

// The free fine nodes.
std::vector<char> free_fine(const std::vector<char>& fine, const std::vector<char>& fixed) {
  std::vector<char> f(fine.size(), 0);
  for (std::size_t i = 0; i < fine.size(); ++i) f[i] = fine[i] && !fixed[i];
  return f;
}

}  // namespace

LocalTimeStepping::LocalTimeStepping(const CsrMatrix& K, const Eigen::VectorXd& mass,
                                     const std::vector<char>& fine, const std::vector<char>& fixed,
                                     int substeps, bool single_precision)
    : LocalTimeStepping(
          [&](const SoilOperator::BlockVisit& visit) {
            K.for_each_upper_block([&](std::int32_t i, std::int32_t j, const double* b) {
              double rounded[9];  // (as the step reads them, so that K_p stays symmetric)
              for (int e = 0; e < 9; ++e)
                rounded[e] =
                    single_precision ? static_cast<double>(static_cast<float>(b[e])) : b[e];
              visit(i, j, rounded);
            });
          },
          mass, fine, halo_flags(fine, fixed, K.flagged_neighbours(free_fine(fine, fixed))), fixed,
          substeps) {}

std::vector<char> LocalTimeStepping::halo_flags(const std::vector<char>& fine,
                                                const std::vector<char>& fixed,
                                                const std::vector<std::int32_t>& fine_neighbours) {
  std::vector<char> halo(fine.size(), 0);
  for (std::size_t i = 0; i < fine.size(); ++i)
    halo[i] = !fixed[i] && (fine[i] || fine_neighbours[i] > 0);
  return halo;
}

LocalTimeStepping::LocalTimeStepping(const Blocks& blocks, const Eigen::VectorXd& mass,
                                     const std::vector<char>& fine, const std::vector<char>& halo,
                                     const std::vector<char>& fixed, int substeps)
    : p_(substeps), t_(static_cast<std::size_t>(substeps) + 1, 1.0) {
  if (p_ < 2) throw std::invalid_argument("local time stepping needs at least 2 sub-steps");
  const auto n = static_cast<std::int32_t>(mass.size());
  std::vector<std::int32_t> position(n, -1);  // per node: its place in halo_, or -1
  for (std::int32_t i = 0; i < n; ++i)
    if (fine[i] && !fixed[i]) {
      position[i] = static_cast<std::int32_t>(halo_.size());
      halo_.push_back(i);
    }
  fine_count_ = static_cast<std::int64_t>(halo_.size());
  for (std::int32_t i = 0; i < n; ++i)
    if (position[i] < 0 && halo[i]) {
      position[i] = static_cast<std::int32_t>(halo_.size());
      halo_.push_back(i);
    }
  for (const std::int32_t i : halo_) inv_mass_.push_back(1.0 / mass[i]);
  // K's blocks at halo rows and fine columns, each row's in the order the blocks come (its
  // columns ascending: a row's transposed blocks come from earlier nodes, then its own): counted
  // first, then filled.
  const auto in_row = [&](std::int32_t row, std::int32_t column) {
    return position[row] >= 0 && position[column] >= 0 && position[column] < fine_count_;
  };
  start_.assign(halo_.size() + 1, 0);
  blocks([&](std::int32_t i, std::int32_t j, const double*) {
    if (in_row(i, j)) ++start_[position[i] + 1];
    if (j != i && in_row(j, i)) ++start_[position[j] + 1];
  });
  for (std::size_t h = 0; h < halo_.size(); ++h) start_[h + 1] += start_[h];
  column_.assign(static_cast<std::size_t>(start_.back()), 0);
  block_.assign(9 * static_cast<std::size_t>(start_.back()), 0.0);
  std::vector<std::int64_t> next(start_.begin(), start_.end() - 1);
  blocks([&](std::int32_t i, std::int32_t j, const double* b) {
    if (in_row(i, j)) {
      const std::int64_t e = next[position[i]]++;
      column_[e] = position[j];
      std::copy_n(b, 9, block_.data() + 9 * e);
    }
    if (j != i && in_row(j, i)) {  // K_ji = K_ij^T
      const std::int64_t e = next[position[j]]++;
      column_[e] = position[i];
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d) block_[9 * e + 3 * c + d] = b[3 * d + c];
    }
  });
  const std::size_t size = 3 * halo_.size();
  for (auto* v : {&g_, &s_prev_, &s_cur_, &s_next_}) v->assign(size, 0.0);
}

double LocalTimeStepping::tau_for(double dt, double a1, double margin) {
  // dt^2 l(M^-1 K_p) <= 2 (1 + 1/tau), i.e. c <= (1 + 1/tau) / 2, must meet c <= margin /
  // (1 + 2 a1 / dt): the lag's limit dt w <= 2 (sqrt(1 + xi^2) - xi), xi = a1 w / 2, squared.
  const double c = margin / (1.0 + 2.0 * a1 / dt);
  const double inverse = 2.0 * c - 1.0;  // 1 / tau
  return inverse > 0.0 ? std::max(1.0, 1.0 / inverse) : 0.0;
}

namespace {

struct Chebyshev {
  double theta, w0, w1;
};

// T_p(w0) = cosh(p theta) = tau; w1 = dt^2 tau / (2 T_p'(w0)), T_p'(w0) = p sinh(p theta) /
// sinh(theta) (p^2 in the limit theta -> 0).
Chebyshev chebyshev(double dt, double tau, int p) {
  const double theta = std::acosh(tau) / p;
  const double slope = theta < 1e-8 ? double(p) * p : p * std::sinh(p * theta) / std::sinh(theta);
  return {theta, std::cosh(theta), dt * dt * tau / (2.0 * slope)};
}

}  // namespace

double LocalTimeStepping::fine_range(double dt, double tau, int substeps) {
  const Chebyshev c = chebyshev(dt, tau, substeps);
  return (1.0 + c.w0) / c.w1;
}

void LocalTimeStepping::set_step(double dt, double tau) {
  if (!(dt > 0.0) || !(tau >= 1.0))
    throw std::invalid_argument("local time stepping: step and tau must be > 0 and >= 1");
  dt_ = dt;
  tau_ = tau;
  const Chebyshev c = chebyshev(dt, tau, p_);
  w0_ = c.w0;
  w1_ = c.w1;
  for (int k = 0; k <= p_; ++k) t_[k] = std::cosh(k * c.theta);
}

void LocalTimeStepping::sum_over_ranks(std::int32_t shared_nodes,
                                       std::function<void(double*, int)> sum) {
  shared_halo_.clear();
  for (std::size_t h = 0; h < halo_.size(); ++h)
    if (halo_[h] < shared_nodes) shared_halo_.push_back(static_cast<std::int32_t>(h));
  shared_products_.assign(3 * static_cast<std::size_t>(shared_nodes), 0.0);
  product_.assign(3 * halo_.size(), 0.0);
  sum_ = std::move(sum);
}

void LocalTimeStepping::apply(double* forces) const {
  // S_k = s_k(A P) A y with T_k(w0 - w1 l) = T_k(w0) + l s_k(l):
  //   S_0 = 0, S_1 = -w1 g, S_(k+1) = 2 w0 S_k - 2 w1 A P S_k - S_(k-1) - 2 w1 T_k(w0) g,
  // g = M^-1 forces (A y for K y); then R(A P) g = S_p / tau, and the result is
  // -(2 / dt^2) M S_p / tau (K_p y for K y).
  const auto halo = static_cast<std::int64_t>(halo_.size());
  double* buffer[3] = {s_prev_.data(), s_cur_.data(), s_next_.data()};
  double* g = g_.data();
#pragma omp for schedule(static)
  for (std::int64_t h = 0; h < halo; ++h)
    for (int c = 0; c < 3; ++c) {
      const std::int64_t k = 3 * h + c;
      g[k] = inv_mass_[h] * forces[k];
      buffer[0][k] = 0.0;
      buffer[1][k] = -w1_ * g[k];
    }
  double* product = product_.data();
  for (int step = 1; step < p_; ++step) {
    const double* previous = buffer[(step - 1) % 3];
    const double* current = buffer[step % 3];
    double* next = buffer[(step + 1) % 3];
    // Halo node h's row of K at the fine columns times S_k, and its S_(k+1) from that.
    const auto row_product = [&](std::int64_t h, double sum[3]) {
      sum[0] = sum[1] = sum[2] = 0.0;
      for (std::int64_t e = start_[h]; e < start_[h + 1]; ++e) {
        const double* b = block_.data() + 9 * e;
        const double* x = current + 3 * static_cast<std::int64_t>(column_[e]);
        for (int c = 0; c < 3; ++c)
          sum[c] += b[3 * c] * x[0] + b[3 * c + 1] * x[1] + b[3 * c + 2] * x[2];
      }
    };
    const auto update = [&](std::int64_t h, const double sum[3]) {
      for (int c = 0; c < 3; ++c) {
        const std::int64_t k = 3 * h + c;
        next[k] = 2.0 * w0_ * current[k] - 2.0 * w1_ * inv_mass_[h] * sum[c] - previous[k] -
                  2.0 * w1_ * t_[step] * g[k];
      }
    };
    if (!sum_) {
#pragma omp for schedule(static)
      for (std::int64_t h = 0; h < halo; ++h) {
        double sum[3];
        row_product(h, sum);
        update(h, sum);
      }
      continue;
    }
#pragma omp for schedule(static)
    for (std::int64_t h = 0; h < halo; ++h) row_product(h, product + 3 * h);
#pragma omp single
    {  // the shared nodes' products summed over the ranks (one thread; the barrier after)
      for (const std::int32_t h : shared_halo_)
        std::copy_n(product + 3 * h, 3, shared_products_.data() + 3 * halo_[h]);
      sum_(shared_products_.data(), 3);
      for (const std::int32_t h : shared_halo_)
        std::copy_n(shared_products_.data() + 3 * halo_[h], 3, product + 3 * h);
    }
#pragma omp for schedule(static)
    for (std::int64_t h = 0; h < halo; ++h) update(h, product + 3 * h);
  }
  const double* last = buffer[p_ % 3];
  const double scale = -2.0 / (dt_ * dt_ * tau_);
#pragma omp for schedule(static)
  for (std::int64_t h = 0; h < halo; ++h)
    for (int c = 0; c < 3; ++c) forces[3 * h + c] = scale * last[3 * h + c] / inv_mass_[h];
}

std::size_t LocalTimeStepping::bytes() const {
  return halo_.size() * (4 + 8 + 4 * 3 * 8) + start_.size() * 8 + column_.size() * 4 +
         block_.size() * 8 + product_.size() * 8 + shared_halo_.size() * 4 +
         shared_products_.size() * 8;
}

}  // namespace rumble::fem
