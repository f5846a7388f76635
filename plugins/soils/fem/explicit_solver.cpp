#include "explicit_solver.hpp"

#include <cmath>
#include <cstdint>

namespace rumble::fem {

ExplicitSolver::ExplicitSolver(CsrMatrix K, Eigen::VectorXd mass,
                               std::vector<BoundaryNode> boundary, bool springs,
                               std::vector<char> fixed, double a0, double a1, unsigned threads)
    : K_(std::move(K)),
      mass_(std::move(mass)),
      boundary_(std::move(boundary)),
      boundary_of_(mass_.size(), -1),
      springs_(springs),
      fixed_(std::move(fixed)),
      a0_(a0),
      a1_(a1),
      threads_(threads < 1 ? 1 : threads),
      y_(Eigen::VectorXd::Zero(3 * mass_.size())) {
  for (std::size_t k = 0; k < boundary_.size(); ++k)
    boundary_of_[boundary_[k].node] = static_cast<std::int32_t>(k);
  estimate_stable_step();
}

std::size_t ExplicitSolver::bytes() const {
  return K_.bytes() + static_cast<std::size_t>(mass_.size()) * (8 + 4 + 1 + 3 * 8) +
         boundary_.size() * sizeof(BoundaryNode) + (pml_ ? pml_->bytes() : 0);
}

ExplicitState ExplicitSolver::rest_state() const {
  const Eigen::Index n = dofs();
  return {Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n),
          Eigen::VectorXd::Zero(pml_ ? pml_->memory_size() : 0)};
}

void ExplicitSolver::set_pml(PmlLayer layer) {
  pml_.emplace(std::move(layer));
  pml_forces_.assign(12 * pml_->tetrahedra(), 0.0);
  if (pml_->max_damping() > 0.0)
    stable_step_ = std::min(stable_step_, PmlLayer::kStableDampingStep / pml_->max_damping());
}

void ExplicitSolver::stiffness_times(const Eigen::VectorXd& x, Eigen::VectorXd& y,
                                     bool with_springs) const {
  const std::int64_t n = mass_.size();
  y.resize(x.size());
#pragma omp parallel for num_threads(threads_) schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) y[3 * i + c] = fixed_[i] ? 0.0 : K_.row_dot(3 * i + c, x.data());
    const std::int32_t b = boundary_of_[i];
    if (with_springs && b >= 0 && !fixed_[i]) {
      const BoundaryNode& node = boundary_[b];
      BoundaryNode::apply(node.normal, node.spring_normal, node.spring_tangential, x.data() + 3 * i,
                          y.data() + 3 * i);
    }
  }
}

void ExplicitSolver::estimate_stable_step() {
  // Power iteration on M^-1 (K + S) over the free DOFs, with the generalized Rayleigh quotient
  // x^T (K + S) x / x^T M x (a lower bound of the largest eigenvalue that converges to it).
  const std::int64_t n = mass_.size();
  Eigen::VectorXd x(3 * n), y;
  std::uint64_t seed = 0x9E3779B97F4A7C15ull;  // fixed: the same step on every run
  for (std::int64_t k = 0; k < 3 * n; ++k) {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    x[k] = fixed_[k / 3] ? 0.0 : static_cast<double>(seed >> 11) / 9007199254740992.0 - 0.5;
  }
  const auto mass_norm = [&](const Eigen::VectorXd& z) {
    double s = 0.0;
    for (std::int64_t k = 0; k < 3 * n; ++k) s += mass_[k / 3] * z[k] * z[k];
    return std::sqrt(s);
  };
  x /= mass_norm(x);
  std::vector<double> history;
  double lambda = 0.0;
  for (power_iterations_ = 1; power_iterations_ <= 3000; ++power_iterations_) {
    stiffness_times(x, y, springs_);
    lambda = x.dot(y);  // x is M-normalized
    history.push_back(lambda);
    for (std::int64_t k = 0; k < 3 * n; ++k) x[k] = y[k] / mass_[k / 3];
    x /= mass_norm(x);
    constexpr std::size_t kLag = 10;
    if (history.size() > kLag &&
        std::abs(lambda - history[history.size() - 1 - kLag]) < 1e-6 * lambda)
      break;
  }
  omega_max_ = std::sqrt(1.02 * lambda);  // 2 % margin for what the iteration has not reached
  const double xi = 0.5 * a1_ * omega_max_;
  stable_step_ = 2.0 / omega_max_ * (std::sqrt(1.0 + xi * xi) - xi);
}

void ExplicitSolver::step(ExplicitState& s, const Eigen::VectorXd& f, double dt) const {
  const std::int64_t n = mass_.size();
  double* w = s.w.data();
  double* v = s.v.data();
  double* a = s.a.data();
  double* y = y_.data();
  const double half = 0.5 * dt;
  if (pml_ && s.pml.size() != pml_->memory_size())
    s.pml = Eigen::VectorXd::Zero(pml_->memory_size());
  double* memory = pml_ ? s.pml.data() : nullptr;
#pragma omp parallel num_threads(threads_)
  {
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) {
      if (fixed_[i]) continue;
      for (std::int64_t k = 3 * i; k < 3 * i + 3; ++k) {
        v[k] += half * a[k];
        w[k] += dt * v[k];
        y[k] = w[k] + a1_ * v[k];
      }
    }
    // (the implicit barrier of omp for: every w and y is updated before K reads them)
    if (pml_) pml_->update_tetrahedra(w, dt, memory, pml_forces_.data());  // (omp for: barrier)
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) {
      if (fixed_[i]) continue;
      double r[3], rhs[3];
      K_.node_rows_dot(static_cast<std::int32_t>(i), y, r);
      for (int c = 0; c < 3; ++c) r[c] = f[3 * i + c] - r[c];
      const double m = mass_[i];
      double inertia = m * (1.0 + half * a0_);
      if (const std::int32_t p = pml_ ? pml_->layer_node(i) : -1; p >= 0) {
        double stretched[3] = {0.0, 0.0, 0.0};
        pml_->gather(p, pml_forces_.data(), stretched);
        double w_old[3];
        for (int c = 0; c < 3; ++c) w_old[c] = w[3 * i + c] - dt * v[3 * i + c];  // v is v+ here
        pml_->add_node_forces(p, w_old, w + 3 * i, dt, memory, stretched);
        for (int c = 0; c < 3; ++c) r[c] -= stretched[c];
        inertia += half * pml_->damping(p);
      }
      const std::int32_t b = boundary_of_[i];
      if (b < 0) {
        for (int c = 0; c < 3; ++c) {
          const std::int64_t k = 3 * i + c;
          const double v_new = (m * v[k] + half * r[c]) / inertia;
          a[k] = (v_new - v[k]) / half;
          v[k] = v_new;
        }
        continue;
      }
      const BoundaryNode& node = boundary_[b];
      if (springs_) {
        double spring[3] = {0.0, 0.0, 0.0};
        BoundaryNode::apply(node.normal, node.spring_normal, node.spring_tangential, w + 3 * i,
                            spring);
        for (int c = 0; c < 3; ++c) r[c] -= spring[c];
      }
      for (int c = 0; c < 3; ++c) rhs[c] = m * v[3 * i + c] + half * r[c];
      // (inertia I + dt/2 D)^-1 = nn^T / (inertia + dt/2 d_n) + (I - nn^T) / (inertia + dt/2 d_t)
      const Eigen::Vector3d& nrm = node.normal;
      const double along = nrm[0] * rhs[0] + nrm[1] * rhs[1] + nrm[2] * rhs[2];
      const double inv_n = 1.0 / (inertia + half * node.dashpot_normal);
      const double inv_t = 1.0 / (inertia + half * node.dashpot_tangential);
      for (int c = 0; c < 3; ++c) {
        const std::int64_t k = 3 * i + c;
        const double v_new = inv_t * (rhs[c] - along * nrm[c]) + inv_n * along * nrm[c];
        a[k] = (v_new - v[k]) / half;
        v[k] = v_new;
      }
    }
  }
}

void ExplicitSolver::force_jump(ExplicitState& s, const Eigen::VectorXd& df) const {
  for (Eigen::Index k = 0; k < df.size(); ++k)
    if (df[k] != 0.0 && !fixed_[k / 3]) s.a[k] += df[k] / mass_[k / 3];
}

double ExplicitSolver::kinetic_energy(const ExplicitState& s) const {
  double e = 0.0;
  for (Eigen::Index k = 0; k < s.v.size(); ++k) e += 0.5 * mass_[k / 3] * s.v[k] * s.v[k];
  return e;
}

double ExplicitSolver::strain_energy(const ExplicitState& s) const {
  Eigen::VectorXd y;
  stiffness_times(s.w, y, springs_);
  return 0.5 * s.w.dot(y);
}

}  // namespace rumble::fem
