#include "time/explicit_solver.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "operator/csr_operator.hpp"

namespace rumble::fem {

ExplicitSolver::ExplicitSolver(CsrMatrix K, Eigen::VectorXd mass,
                               std::vector<BoundaryNode> boundary, bool springs,
                               std::vector<char> fixed, double a0, double a1, unsigned threads,
                               StepPrecision precision)
    : ExplicitSolver(
          std::make_unique<CsrOperator>(std::move(K), std::move(mass), std::move(boundary), springs,
                                        std::move(fixed), threads, precision),
          a0, a1) {}

ExplicitSolver::ExplicitSolver(std::unique_ptr<SoilOperator> op, double a0, double a1)
    : ExplicitSolver(std::move(op), a0, a1, 0.0, 0) {}

ExplicitSolver::ExplicitSolver(std::unique_ptr<SoilOperator> op, double a0, double a1,
                               double largest_eigenvalue, int iterations)
    : op_(std::move(op)),
      csr_(dynamic_cast<const CsrOperator*>(op_.get())),
      mass_(op_->mass().data()),
      boundary_(op_->boundary().data()),
      boundary_of_(op_->boundary_of().data()),
      fixed_(op_->fixed().data()),
      springs_(op_->springs_act()),
      a0_(a0),
      a1_(a1),
      lambda_max_(largest_eigenvalue),
      eigen_iterations_(iterations),
      y_(Eigen::VectorXd::Zero(op_->dofs())) {
  if (largest_eigenvalue <= 0.0) {
    estimate_stable_step();
    return;
  }
  omega_max_ = std::sqrt(lambda_max_ * maxwell_.unrelaxed());
  single_rate_step_ = step_limit(lambda_max_ / 1.02);
}

std::size_t ExplicitSolver::bytes() const {
  const auto nodes = static_cast<std::size_t>(op_->nodes());
  return op_->bytes() + static_cast<std::size_t>(maxwell_.mechanisms()) * 3 * nodes * 4 +
         nodes * 3 * 8 + (pml_ ? pml_->bytes() : 0) +
         (lts_ ? lts_->bytes() + halo_of_.size() * 4 + halo_forces_.size() * 8 : 0);
}

ExplicitState ExplicitSolver::rest_state() const {
  const Eigen::Index n = dofs();
  return {Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n),
          Eigen::VectorXd::Zero(pml_ ? pml_->memory_size() : 0),
          Eigen::VectorXf::Zero(maxwell_.mechanisms() * n)};
}

void ExplicitSolver::set_maxwell_damping(MaxwellDamping d) {
  if (lts_) throw std::logic_error("ExplicitSolver: set_maxwell_damping after the local steps");
  maxwell_ = std::move(d);
  omega_max_ = std::sqrt(lambda_max_ * maxwell_.unrelaxed());
  single_rate_step_ = step_limit(lambda_max_ / 1.02);
}

void ExplicitSolver::set_pml(PmlLayer layer) {
  pml_.emplace(std::move(layer));
  pml_forces_.assign(12 * pml_->tetrahedra(), 0.0);
  pml_shared_.assign(3 * static_cast<std::size_t>(op_->shared_nodes()), 0.0);
  if (pml_->max_damping() > 0.0) pml_step_ = PmlLayer::kStableDampingStep / pml_->max_damping();
}

namespace {

// The largest stable step [s] of the central difference with the damping a1 K at the half-step
// velocity, for the largest circular frequency omega [rad/s]: xi = a1 omega / 2 its damping ratio.
double damped_step(double omega, double a1) {
  const double xi = 0.5 * a1 * omega;
  return 2.0 / omega * (std::sqrt(1.0 + xi * xi) - xi);
}

}  // namespace

namespace {

// The start of the eigenvalue iterations: x -> a x + c (mod 2^64) from a fixed seed, its k-th
// state giving DOF k - 1 of the whole mesh.
constexpr std::uint64_t kLcgSeed = 0x9E3779B97F4A7C15ull;
constexpr std::uint64_t kLcgMultiplier = 6364136223846793005ull;
constexpr std::uint64_t kLcgIncrement = 1442695040888963407ull;

// The generator's state after `steps` steps from its seed, by repeated squaring of the affine
// map (Brown's skip-ahead): O(log steps), so that each rank starts at its own nodes' DOFs.
std::uint64_t start_seed(std::uint64_t steps) {
  std::uint64_t mul = 1, add = 0, step_mul = kLcgMultiplier, step_add = kLcgIncrement;
  for (; steps > 0; steps >>= 1) {
    if (steps & 1u) {
      mul *= step_mul;
      add = add * step_mul + step_add;
    }
    step_add = (step_mul + 1) * step_add;
    step_mul *= step_mul;
  }
  return mul * kLcgSeed + add;
}

}  // namespace

double ExplicitSolver::largest_eigenvalue(
    const std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>& op,
    int& iterations) const {
  // Lanczos on M^-1 op, self-adjoint in the M inner product, over the free DOFs, without
  // reorthogonalization: only the largest eigenvalue is wanted, and the largest eigenvalue of the
  // tridiagonal T_j (a Rayleigh quotient over the Krylov space, so a lower bound, as the power
  // iteration's was) converges to it in far fewer products (lost orthogonality only repeats
  // converged eigenvalues). Three vectors; T_j's eigenvalues by Eigen's tridiagonal QR, O(j^2) per
  // iteration.
  // Ours rather than Spectra's (issue #31 item 7, docs/fem-soil.md section 4; measured on
  // 2026-12-05 on the step benchmark's Kuhn box of the medium soil, one thread, best of 3 on a
  // loaded 2-core machine): Spectra 1.0's
  // SymEigsSolver on M^-1/2 K M^-1/2 over the free DOFs (the largest eigenvalue only, a basis of
  // 20 vectors, tolerance 1e-7, which keeps the single- and double-precision steps within 1e-6 of
  // each other as this loop does) took 2.8 times this loop's time at 1.1e5 DOFs (0.43 s against
  // 0.15 s; 91 products against 82) and 3.9 times at 3.5e5 DOFs (2.50 s against 0.64 s; 101
  // against 87), for the same eigenvalue to 2.5e-11: its restarted Lanczos reorthogonalizes each
  // vector against its whole basis, which costs more than the product itself here, and keeps that
  // basis (0.5 GB at 3e6 DOFs) against our three vectors. A basis of 10 took 2.1 and 3.3 times;
  // at tolerance 1e-3 (still far inside the 2 % margin) 0.96 and 1.19 times, its eigenvalue then
  // 2.6e-4 and 5.4e-4 low.
  const std::int64_t n = op_->nodes();
  const unsigned threads = op_->threads();
  Eigen::VectorXd q(3 * n), q_prev = Eigen::VectorXd::Zero(3 * n), w;
  for (std::int64_t i = 0; i < n; ++i) {  // (fixed: the same step on every run and rank count)
    std::uint64_t seed = start_seed(3 * static_cast<std::uint64_t>(op_->whole_node(i)));
    for (int c = 0; c < 3; ++c) {
      seed = seed * kLcgMultiplier + kLcgIncrement;
      q[3 * i + c] = fixed_[i] ? 0.0 : static_cast<double>(seed >> 11) / 9007199254740992.0 - 0.5;
    }
  }
  const auto mass_norm = [&](const Eigen::VectorXd& z) { return std::sqrt(op_->dot(z, z, mass_)); };
  q /= mass_norm(q);
  std::vector<double> alpha, beta, history;
  double lambda = 0.0;
  constexpr int kMaxIterations = 3000;
  for (iterations = 1; iterations <= kMaxIterations; ++iterations) {
    check_stop();
    op(q, w);                                  // K q
    const double a = op_->dot(q, w, nullptr);  // q^T K q, q M-normalized
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::int64_t k = 0; k < 3 * n; ++k)
      w[k] = w[k] / mass_[k / 3] - a * q[k] - (beta.empty() ? 0.0 : beta.back() * q_prev[k]);
    alpha.push_back(a);
    const double b = mass_norm(w);
    // Overflowed stiffness or mass (a modulus or density far outside any soil's) would make the
    // tridiagonal QR below loop for ever on NaN: refuse with what to change.
    if (!std::isfinite(a) || !std::isfinite(b)) {
      throw std::runtime_error(
          "fem: the largest vibration frequency of the mesh, which sets the stable step, is not "
          "finite (its stiffness or mass overflowed): E, rho and the mesh sizes must be physical "
          "(rumble schema fem gives their ranges)");
    }
    const auto j = static_cast<Eigen::Index>(alpha.size());
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> tridiagonal;
    tridiagonal.computeFromTridiagonal(Eigen::Map<const Eigen::VectorXd>(alpha.data(), j),
                                       Eigen::Map<const Eigen::VectorXd>(beta.data(), j - 1),
                                       Eigen::EigenvaluesOnly);
    lambda = tridiagonal.eigenvalues().maxCoeff();
    history.push_back(lambda);
    constexpr std::size_t kLag = 5;
    if (b <= 1e-14 * std::abs(a) ||  // an invariant subspace: T's eigenvalues are exact
        (history.size() > kLag &&
         std::abs(lambda - history[history.size() - 1 - kLag]) < 1e-9 * lambda))
      break;
    beta.push_back(b);
    q_prev.swap(q);
    q = w / b;
  }
  return lambda;
}

void ExplicitSolver::estimate_stable_step() {
  const double lambda = largest_eigenvalue(
      [this](const Eigen::VectorXd& x, Eigen::VectorXd& y) {
        op_->stepped_stiffness_times(x, y, springs_);
      },
      eigen_iterations_);
  lambda_max_ = 1.02 * lambda;  // 2 % margin for what the iteration has not reached
  omega_max_ = std::sqrt(lambda_max_ * maxwell_.unrelaxed());
  single_rate_step_ = step_limit(lambda);
}

double ExplicitSolver::step_limit(double lambda) const {
  return damped_step(std::sqrt(1.02 * lambda * maxwell_.unrelaxed()), a1_);
}

void ExplicitSolver::effective_stiffness_times(const Eigen::VectorXd& x, Eigen::VectorXd& y,
                                               double dt) const {
  op_->stepped_stiffness_times(x, y, springs_);
  if (!lts_ || dt <= one_rate_limit_) return;
  prepare_local_steps(dt);
  filter_halo(y.data(), [&](std::int64_t node, const double* filtered) {
    std::copy_n(filtered, 3, y.data() + 3 * node);
  });
}

template <class Take>
void ExplicitSolver::filter_halo(const double* forces, Take&& take) const {
  const std::vector<std::int32_t>& halo = lts_->halo();
  const auto count = static_cast<std::int64_t>(halo.size());
  double* buffer = halo_forces_.data();
#pragma omp parallel num_threads(op_->threads())
  {
#pragma omp for schedule(static)
    for (std::int64_t h = 0; h < count; ++h)
      for (int c = 0; c < 3; ++c) buffer[3 * h + c] = forces[3 * halo[h] + c];
    lts_->apply(buffer);  // (orphaned omp for loops)
#pragma omp for schedule(static)
    for (std::int64_t h = 0; h < count; ++h) take(halo[h], buffer + 3 * h);
  }
}

void ExplicitSolver::prepare_local_steps(double dt) const {
  if (dt == lts_->step()) return;
  const double tau = LocalTimeStepping::tau_for(dt, a1_);
  if (tau == 0.0 ||
      omega_max_ * omega_max_ > LocalTimeStepping::fine_range(dt, tau, lts_->substeps()))
    throw std::logic_error("local time stepping cannot take a step of " + std::to_string(dt) +
                           " s on this mesh (its verified step is " + std::to_string(local_step_) +
                           " s)");
  lts_->set_step(dt, tau);
}

namespace {

/// The Maxwell mechanisms' exact update over a step of dt [s] for a displacement linear over it,
/// z <- decay z + gain dw, and each mechanism's weight in the memory force.
struct MechanismUpdate {
  std::array<double, MaxwellDamping::kMaxMechanisms> decay{}, gain{}, weight{};
};

MechanismUpdate mechanism_update(const MaxwellDamping& maxwell, double dt) {
  MechanismUpdate u;
  for (int l = 0; l < maxwell.mechanisms(); ++l) {
    const double rate_dt = maxwell.rates[l] * dt;
    u.decay[l] = std::exp(-rate_dt);
    u.gain[l] = -std::expm1(-rate_dt) / rate_dt;
    u.weight[l] = maxwell.weights[l];
  }
  return u;
}

/// Node i's new velocity and acceleration where only its mass and the a0 damping act (no
/// boundary block, not in the matched layer, not at the local steps' halo):
///   m (1 + dt/2 a0) v' = m v+ + dt/2 (f - K y),   a = (v' - v+) / (dt/2),
/// by the reciprocals: one division per node, where six were half of the step's time on an
/// AVX-512 machine (docs/fem-soil.md §4.3). product: K y at the node; f, v, a: its 3 DOFs.
struct VelocityUpdate {
  double half, per_half, factor;  // dt/2 [s], 2/dt [1/s], 1 + dt/2 a0
  void operator()(double m, const double* product, const double* f, double* v, double* a) const {
    const double inverse = 1.0 / (m * factor);
    for (int c = 0; c < 3; ++c) {
      const double v_new = (m * v[c] + half * (f[c] - product[c])) * inverse;
      a[c] = (v_new - v[c]) * per_half;
      v[c] = v_new;
    }
  }
};

}  // namespace

void ExplicitSolver::predict(ExplicitState& s, double dt) const {
  const std::int64_t n = op_->nodes();
  double* w = s.w.data();
  double* v = s.v.data();
  const double* a = s.a.data();
  double* y = y_.data();
  const double half = 0.5 * dt;
  const int mechanisms = maxwell_.mechanisms();
  if (mechanisms == 0) {
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) {
      if (fixed_[i]) continue;
      for (std::int64_t k = 3 * i; k < 3 * i + 3; ++k) {
        v[k] += half * a[k];
        w[k] += dt * v[k];
        y[k] = w[k] + a1_ * v[k];
      }
    }
    return;
  }
  float* z = s.maxwell.data();
  const MechanismUpdate update = mechanism_update(maxwell_, dt);
  const auto &decay = update.decay, &gain = update.gain, &weight = update.weight;
#pragma omp for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    if (fixed_[i]) continue;
    for (std::int64_t k = 3 * i; k < 3 * i + 3; ++k) {
      v[k] += half * a[k];
      const double dw = dt * v[k];
      w[k] += dw;
      double memory_force = 0.0;  // sum_l c_l z_l
      float* zk = z + mechanisms * k;
      for (int l = 0; l < mechanisms; ++l) {
        zk[l] = static_cast<float>(decay[l] * zk[l] + gain[l] * dw);
        memory_force += weight[l] * zk[l];  // (the value kept, so restarts repeat it)
      }
      y[k] = w[k] + memory_force;
    }
  }
}

void ExplicitSolver::step(ExplicitState& s, const Eigen::VectorXd& f, double dt) const {
  double* w = s.w.data();
  double* v = s.v.data();
  double* a = s.a.data();
  double* y = y_.data();
  const double half = 0.5 * dt;
  if (pml_ && s.pml.size() != pml_->memory_size())
    s.pml = Eigen::VectorXd::Zero(pml_->memory_size());
  double* memory = pml_ ? s.pml.data() : nullptr;
  const bool local = lts_ && dt > one_rate_limit_;
  if (local) prepare_local_steps(dt);
  last_step_local_ = local;
  const int mechanisms = maxwell_.mechanisms();
  if (mechanisms > 0 && s.maxwell.size() != mechanisms * dofs())
    s.maxwell = Eigen::VectorXf::Zero(mechanisms * dofs());
  const VelocityUpdate plain{half, 2.0 / dt, 1.0 + half * a0_};
#pragma omp parallel num_threads(op_->threads())
  {
    predict(s, dt);
    // (the implicit barrier of omp for: every w and y is updated before K reads them)
    if (pml_) pml_->update_tetrahedra(w, dt, memory, pml_forces_.data());  // (omp for: barrier)
    if (pml_ && op_->spans_ranks()) sum_pml_over_ranks();
    // Each node once the product has handed over its K y: the residual, then the node's velocity
    // and acceleration, or at the halo under local steps the residual kept for the filter below.
    // (always inlined into the product's loop: a call per node costs more than the update)
    const auto finish = [&](std::int64_t i, const double* product) __attribute__((always_inline)) {
      if (fixed_[i]) return;
      if (boundary_of_[i] < 0 && !(local && halo_of_[i] >= 0) &&
          !(pml_ && pml_->layer_node(i) >= 0))
        return plain(mass_[i], product, f.data() + 3 * i, v + 3 * i, a + 3 * i);
      double r[3] = {product[0], product[1], product[2]};
      residual(i, w, f, r);
      if (local && halo_of_[i] >= 0)
        std::copy_n(r, 3, halo_forces_.data() + 3 * halo_of_[i]);
      else
        finish_node(i, r, dt, s, memory);
    };
    if (csr_) {  // the CSR back end's fused product: the finish inlined in its loop
      csr_->fused_product(y, finish);
    } else {
      NodeProductsOf take(finish);
      op_->stepped_product(y, take);
    }
    if (local) {
#pragma omp barrier
      // (every halo residual is in: the product hands nodes over with no barrier of its own)
      lts_->apply(halo_forces_.data());  // (orphaned omp for loops: barriers)
      const std::vector<std::int32_t>& halo = lts_->halo();
      const auto count = static_cast<std::int64_t>(halo.size());
#pragma omp for schedule(static)
      for (std::int64_t h = 0; h < count; ++h)
        finish_node(halo[h], halo_forces_.data() + 3 * h, dt, s, memory);
    }
  }
}

void ExplicitSolver::sum_pml_over_ranks() const {
  const auto shared = static_cast<std::int64_t>(pml_shared_.size() / 3);
  double* summed = pml_shared_.data();
#pragma omp for schedule(static)
  for (std::int64_t i = 0; i < shared; ++i) {
    std::fill_n(summed + 3 * i, 3, 0.0);
    if (const std::int32_t p = pml_->layer_node(i); p >= 0)
      pml_->gather(p, pml_forces_.data(), summed + 3 * i);
  }
#pragma omp master
  op_->sum_shared_nodes(summed, 3);
#pragma omp barrier
}

void ExplicitSolver::residual(std::int64_t i, const double* w, const Eigen::VectorXd& f,
                              double out[3]) const {
  if (const std::int32_t b = springs_ ? boundary_of_[i] : -1; b >= 0) {
    const BoundaryNode& node = boundary_[b];
    node.apply_spring(w + 3 * i, out);
  }
  for (int c = 0; c < 3; ++c) out[c] -= f[3 * i + c];
}

void ExplicitSolver::finish_node(std::int64_t i, const double residual[3], double dt,
                                 ExplicitState& s, double* memory) const {
  double* w = s.w.data();
  double* v = s.v.data();
  double* a = s.a.data();
  const double half = 0.5 * dt;
  double r[3], rhs[3];
  for (int c = 0; c < 3; ++c) r[c] = -residual[c];
  const double m = mass_[i];
  double inertia = m * (1.0 + half * a0_);
  if (const std::int32_t p = pml_ ? pml_->layer_node(i) : -1; p >= 0) {
    double stretched[3] = {0.0, 0.0, 0.0};
    if (3 * static_cast<std::size_t>(i) < pml_shared_.size())  // (summed over the ranks)
      std::copy_n(pml_shared_.data() + 3 * i, 3, stretched);
    else
      pml_->gather(p, pml_forces_.data(), stretched);
    double w_old[3];
    for (int c = 0; c < 3; ++c) w_old[c] = w[3 * i + c] - dt * v[3 * i + c];  // v is v+ here
    pml_->add_node_forces(p, w_old, w + 3 * i, dt, memory, stretched);
    for (int c = 0; c < 3; ++c) r[c] -= stretched[c];
    inertia += half * pml_->damping(p);
  }
  const std::int32_t b = boundary_of_[i];
  const double per_half = 2.0 / dt;  // (multiplies, not divisions: VelocityUpdate)
  if (b < 0) {
    const double inverse = 1.0 / inertia;
    for (int c = 0; c < 3; ++c) {
      const std::int64_t k = 3 * i + c;
      const double v_new = (m * v[k] + half * r[c]) * inverse;
      a[k] = (v_new - v[k]) * per_half;
      v[k] = v_new;
    }
    return;
  }
  const BoundaryNode& node = boundary_[b];
  for (int c = 0; c < 3; ++c) rhs[c] = m * v[3 * i + c] + half * r[c];
  // (inertia I + dt/2 D)^-1 = nn^T / (inertia + dt/2 d_n) + (I - nn^T) / (inertia + dt/2 d_t)
  const Eigen::Vector3d& nrm = node.normal;
  const double along = nrm[0] * rhs[0] + nrm[1] * rhs[1] + nrm[2] * rhs[2];
  const double inv_n = 1.0 / (inertia + half * node.dashpot_normal);
  const double inv_t = 1.0 / (inertia + half * node.dashpot_tangential);
  for (int c = 0; c < 3; ++c) {
    const std::int64_t k = 3 * i + c;
    const double v_new = inv_t * (rhs[c] - along * nrm[c]) + inv_n * along * nrm[c];
    a[k] = (v_new - v[k]) * per_half;
    v[k] = v_new;
  }
}

void ExplicitSolver::set_loaded_nodes(std::vector<std::int32_t> nodes) {
  std::vector<char> seen(static_cast<std::size_t>(op_->nodes()), 0);
  for (const std::int32_t i : nodes) {
    if (seen[i]) throw std::invalid_argument("ExplicitSolver: a loaded node given twice");
    seen[i] = 1;
  }
  loaded_nodes_ = std::move(nodes);
  every_node_loaded_ = false;
}

void ExplicitSolver::force_jump(ExplicitState& s, const Eigen::VectorXd& df) const {
  // Under local time stepping the halo's accelerations are filtered residuals, so is the jump
  // (with the coefficients of the last step, whose acceleration this is): there the whole halo
  // takes its filtered share, elsewhere only the loaded nodes change.
  const bool local = last_step_local_;
  const auto add = [&](std::int64_t i) {
    if (fixed_[i] || (local && halo_of_[i] >= 0)) return;
    for (int c = 0; c < 3; ++c) s.a[3 * i + c] += df[3 * i + c] / mass_[i];
  };
  if (every_node_loaded_)
    for (std::int64_t i = 0; i < op_->nodes(); ++i) add(i);
  else
    for (const std::int32_t i : loaded_nodes_) add(i);
  if (!local) return;
  filter_halo(df.data(), [&](std::int64_t node, const double* filtered) {
    for (int c = 0; c < 3; ++c) s.a[3 * node + c] += filtered[c] / mass_[node];
  });
}

double ExplicitSolver::kinetic_energy(const ExplicitState& s) const {
  double e = 0.0;
  for (Eigen::Index k = 0; k < s.v.size(); ++k) e += 0.5 * mass_[k / 3] * s.v[k] * s.v[k];
  return e;
}

double ExplicitSolver::strain_energy(const ExplicitState& s) const {
  Eigen::VectorXd y;
  op_->stepped_stiffness_times(s.w, y, springs_);
  return 0.5 * s.w.dot(y);
}

}  // namespace rumble::fem
