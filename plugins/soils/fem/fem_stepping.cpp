// The FEM soil in time: the static state, the macro steps cut into sub-steps, the footprint
// forces and the far field's traction that drive them, the team of threads and the checkpoints.
// Kept together because they share the stepped state and its invariants (which forces the state
// holds, when the far field lags), which no other concern of the plugin writes.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "boundary/static_far_field.hpp"
#include "fem_soil.hpp"
#include "operator/footprint_loads.hpp"
#include "statics/static_solver.hpp"
#include "time/thread_tuner.hpp"
#include "wave_speeds.hpp"

namespace rumble::fem {

namespace {

/// Sub-steps in one macro step, at most (as the lumped soils): beyond, a macro step is a mistake.
constexpr double kMaxSubSteps = 1e9;

}  // namespace

void FemSoil::initialize(double t0, const double* static_force, double* static_u) {
  require_layout("initialize");
  if (distributed_) return initialize_distributed(t0, static_force, static_u);
  initialize_here(t0, static_force, static_u);
}

void FemSoil::initialize_here(double /*t0*/, const double* static_force, double* static_u) {
  export_if_due();  // a run's soil was laid out by its validation, before it had a directory
  op_->set_threads(host_.threads());  // the statics' products use them
  force_static_.assign(static_force, static_force + footprints_.size());
  force_last_ = force_static_;
  spread(force_static_.data(), f_);
  add_static_far_field(force_static_.data(), f_);
  // No static load (a check, or a soil driven by forces alone): no factor needed.
  const auto start = std::chrono::steady_clock::now();
  const bool first_multigrid = statics_->multigrid_levels() == 0;
  u_static_ = f_.isZero(0.0) ? Eigen::VectorXd::Zero(f_.size()) : statics_->solve(f_);
  const std::string solved = "in " + format(seconds_since(start), 2) + " s, " +
                             std::to_string(statics_->last_cg_iterations()) + " CG iterations";
  if (first_multigrid && statics_->multigrid_levels() > 0)  // (once: the hierarchy is kept)
    host_.info("fem: static solves by " + std::string(statics_->method()) + ": " +
               std::to_string(statics_->multigrid_levels()) + " levels (" +
               format(static_cast<double>(statics_->bytes()) / 1048576.0) +
               " MiB besides PETSc's own, which summary.json's statics peak counts), set up in " +
               format(statics_->multigrid_setup_seconds(), 2) +
               " s; the first solve, set-up included, " + solved);
  else if (!statics_->factored() && statics_->last_cg_iterations() > 0)
    host_.log(RUMBLE_LOG_DEBUG,
              "fem: static solve (" + std::string(statics_->method()) + ") " + solved);
  for (Eigen::Index k = 0; k < f_.size(); ++k) f_[k] = 0.0;
  state_.w.setZero();
  state_.v.setZero();
  state_.a.setZero();
  state_.pml.setZero();                             // the layer at rest
  state_.maxwell.setZero();                         // the mechanisms relaxed
  far_lag_.lagged.assign(footprints_.size(), 0.0);  // the boundary holds the static traction
  for (std::size_t j = 0; j < footprints_.size(); ++j) static_u[j] = average(j, u_static_);
  statics_to_free_ = true;
}

void FemSoil::free_statics() {
  const std::size_t before = statics_->bytes() + op_->bytes();
  statics_->release();
  if (!implicit_) op_->release_stiffness();  // (the explicit step reads its own copy of K)
  statics_to_free_ = false;
  host_.log(RUMBLE_LOG_DEBUG,
            "fem: the statics done, " +
                format(static_cast<double>(before - statics_->bytes() - op_->bytes()) / 1048576.0) +
                " MiB freed (their factor or PETSc's hierarchy, K's compressed rows)");
}

void FemSoil::finalize() {
  if (distributed_ && !distributed_->root()) return;  // (rank 0 says it for all)
  // Which team sizes the explicit steps ran on, when the host granted more than one thread:
  // on a busy machine, one thread most of the time (time/thread_tuner.hpp).
  if (tuner_.sizes().size() > 1 && !tuner_.account().empty())
    host_.log(RUMBLE_LOG_INFO, "fem: explicit steps on " + tuner_.account() +
                                   ", each size taken as the machine let it step fastest");
}

void FemSoil::advance(double t, double H, const rumble::Waveform& force) {
  require_layout("advance");
  if (distributed_) return advance_distributed(t, H, force);
  // Granted with the run context, after the layout; the explicit step uses what the tuner finds
  // fastest on this machine now (time/thread_tuner.hpp).
  tuner_.grant(host_.threads());
  op_->set_threads(implicit_ ? host_.threads() : tuner_.threads());
  if (settings_.local_steps > 1 && !implicit_ && !local_steps_chosen_) {
    enable_local_steps(*op_, H, true);
    local_steps_chosen_ = true;
  }
  // The statics are done once the steps begin (a later static solve builds again what it needs).
  if (statics_to_free_) free_statics();
  // Counted in floating point first: a macro step far beyond the soil's step must not overflow
  // the count (any H is cut into equal sub-steps; only their number is bounded).
  const double count = std::ceil(H / max_step() - 1e-9);
  if (!(count <= kMaxSubSteps)) {
    std::ostringstream m;
    m << "fem: a macro step of " << H << " s in " << (implicit_ ? "implicit" : "explicit")
      << " sub-steps of at most " << format(max_step()) << " s is " << count
      << " sub-steps, more than " << kMaxSubSteps << "; lower /time/macro_step";
    throw std::invalid_argument(m.str());
  }
  const int sub_steps = std::max(1, static_cast<int>(count));
  const double dt = H / sub_steps;
  if (H != reported_macro_step_) {  // once at info level, later changes (adaptive H) at debug
    host_.log(reported_macro_step_ < 0.0 ? RUMBLE_LOG_INFO : RUMBLE_LOG_DEBUG,
              "fem: " + std::to_string(sub_steps) + " " + (implicit_ ? "implicit" : "explicit") +
                  " sub-step(s) of " + format(dt) + " s per macro step of " + format(H) + " s, " +
                  std::to_string(op_->threads()) + " thread(s)");
    reported_macro_step_ = H;
  }
  // The force may jump at the step's start (a held or extrapolated waveform): the acceleration
  // at t follows it.
  footprint_forces(force, 0.0, df_, force_last_.data());
  if (far_field_ && settings_.boundary.far_field_follows) follow_far_field(force, H);
  op_->force_jump(state_, df_);
  auto last_check = std::chrono::steady_clock::now();
  for (int k = 1; k <= sub_steps; ++k) {
    const double tau = static_cast<double>(k) / sub_steps;
    footprint_forces(force, tau, f_, force_static_.data());
    const auto start = std::chrono::steady_clock::now();
    if (implicit_) {
      implicit_->step(state_, f_, dt);
    } else {
      op_->step(state_, f_, dt);
      tune_threads(std::chrono::steady_clock::now() - start);
    }
    record_probes(t + tau * H);
    const auto now = std::chrono::steady_clock::now();
    if (now - last_check > std::chrono::milliseconds(100)) {
      host_.check_stop(tau);
      last_check = now;
    }
  }
  for (std::size_t j = 0; j < footprints_.size(); ++j) force_last_[j] = force.at(j, 1.0);
  for (std::size_t j = 0; j < footprints_.size(); ++j)
    if (!std::isfinite(average(j, state_.w)) || !std::isfinite(average(j, state_.v))) {
      std::ostringstream m;
      m << "fem: the motion of footprint " << j << " is not finite at t = " << t + H << " s: "
        << (implicit_
                ? "the forces are not finite"
                : "the explicit step " + format(dt) + " s is unstable (lower params/courant, now " +
                      format(settings_.courant) + ") or the forces are not finite");
      throw std::runtime_error(m.str());
    }
}

void FemSoil::motion(double* u, double* v) const {
  if (distributed_) return motion_distributed(u, v);
  for (std::size_t j = 0; j < footprints_.size(); ++j) {
    u[j] = average(j, u_static_) + average(j, state_.w);
    v[j] = average(j, state_.v);
  }
}

void FemSoil::checkpoint_save(std::uint32_t slot) {
  require_layout("checkpoint_save");
  Checkpoint& c = checkpoints_.at(slot);
  c.state = stepped_state();
  c.force_last = force_last_;
  c.far_lagged = far_lag_.lagged;
  c.next_sample = next_sample_;
  c.valid = true;
}

void FemSoil::checkpoint_restore(std::uint32_t slot) {
  const Checkpoint& c = checkpoints_.at(slot);
  if (!c.valid)
    throw std::logic_error("fem: checkpoint slot " + std::to_string(slot) + " is empty");
  stepped_state() = c.state;
  force_last_ = c.force_last;
  far_lag_.lagged = c.far_lagged;
  next_sample_ = c.next_sample;
}

void FemSoil::footprint_forces(const rumble::Waveform& force, double tau, Eigen::VectorXd& out,
                               const double* reference) const {
  for (const auto& footprint : weights_)
    for (const rumble::fem::NodalWeight& w : footprint) out[3 * w.node + 2] = 0.0;
  for (std::size_t j = 0; j < weights_.size(); ++j) {
    const double F = force.at(j, tau) - reference[j];
    for (const rumble::fem::NodalWeight& w : weights_[j]) out[3 * w.node + 2] += w.weight * F;
  }
}

void FemSoil::spread(const double* force, Eigen::VectorXd& out) const {
  out.setZero();
  for (std::size_t j = 0; j < weights_.size(); ++j)
    for (const rumble::fem::NodalWeight& w : weights_[j])
      out[3 * w.node + 2] += w.weight * force[j];
}

void FemSoil::add_static_far_field(const double* force, Eigen::VectorXd& f) {
  if (const rumble::fem::StaticFarField* far = far_field()) far->add(force, f, op_->threads());
}

const rumble::fem::StaticFarField* FemSoil::far_field() {
  if (!rumble::fem::static_far_field_applies(settings_)) return nullptr;
  if (!far_field_) {
    const auto start = std::chrono::steady_clock::now();
    far_field_.emplace(mesh_, settings_, footprints_, op_->boundary());
    // Its traction changes with the forces, so a force jump acts at its nodes too.
    std::vector<std::int32_t> loaded = rumble::fem::loaded_nodes(weights_);
    loaded.insert(loaded.end(), far_field_->nodes().begin(), far_field_->nodes().end());
    std::sort(loaded.begin(), loaded.end());
    loaded.erase(std::unique(loaded.begin(), loaded.end()), loaded.end());
    op_->set_loaded_nodes(std::move(loaded));
    far_lag_.tau = far_field_->mean_distance() /
                   rumble::soils::slowest_wave_speeds(settings_.layers, settings_.half_space).shear;
    far_lag_.lagged.assign(footprints_.size(), 0.0);
    far_change_.assign(footprints_.size(), 0.0);
    far_step_.assign(footprints_.size(), 0.0);
    host_.log(RUMBLE_LOG_DEBUG,
              "fem: the half-space's static far field in " + format(seconds_since(start), 2) +
                  " s, " + format(far_field_->bytes() / 1048576.0) +
                  " MiB; it follows the forces with a lag of " + format(far_lag_.tau, 3) + " s");
  }
  return &*far_field_;
}

void FemSoil::follow_far_field(const rumble::Waveform& force, double H) {
  for (std::size_t j = 0; j < footprints_.size(); ++j) {
    far_change_[j] = force.at(j, 0.5) - force_static_[j];
    far_step_[j] = far_lag_.lagged[j];  // (the change the boundary held before)
  }
  far_lag_.advance(far_change_, H);
  far_field_->follow(far_step_.data(), far_lag_.lagged.data(), f_, df_, op_->threads());
}

void FemSoil::tune_threads(std::chrono::steady_clock::duration took) {
  tuner_.record(std::chrono::duration<double>(took).count());
  if (tuner_.threads() != op_->threads()) {
    host_.log(RUMBLE_LOG_DEBUG, "fem: the explicit step goes on " +
                                    std::to_string(tuner_.threads()) +
                                    " thread(s), the fastest now");
    op_->set_threads(tuner_.threads());
  }
}

}  // namespace rumble::fem
