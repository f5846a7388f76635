#include "analysis/coupling_stability.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "core/errors.hpp"
#include "run/run_components.hpp"
#include "track/track_participant.hpp"

namespace rumble {
namespace {

// Size of the perturbation, relative to the largest static footprint settlement (1e-4 to 1e-3
// m): it starts at 1e-11 of it (~1e-15 to 1e-14 m; the unperturbed run it is measured against,
// set_reference, is repeated to the bit, so nothing but round-off of the states, ~1e-20 m, is
// below it) and is followed while it stays below 1e-3 of it (~1e-7 m, where the Hertz law is
// linear to about 1e-3). Eight decades: a growth of 1.03 per step is followed for 620 steps.
constexpr double kStartPerturbation = 1e-11;
constexpr double kLargestPerturbation = 1e-3;
// Macro steps followed: at least this many and this much simulated time [s] (the slow modes of
// the track and soil must have settled; measured: 20 ms at H = 0.1 ms left a transient that
// read 1.0025 on stable cases), then doubled until the growth averaged over the second half
// changes by less than kSettled between doublings (a mode that overtakes another close to it
// takes long: Jacobi at 0.5 ms on the massless CLM read 1.009 after 0.1 s, 1.0166 after 0.3 s),
// at most kMaxDoublings times. A deviation that falls below kFloor of its start has left the
// dominant mode to round-off: the steps before it count.
constexpr int kMinIterations = 200;
constexpr double kMinDuration = 0.2;
constexpr double kSettled = 1e-4;
constexpr int kMaxDoublings = 4;
constexpr double kFloor = 1e-6;

/// coeff (order + 1 blocks of now.size()) of the polynomial in tau through the newest samples at
/// equal steps H, evaluated over the next step: the Newton form of the SDK's
/// OutputHistory::extrapolate (rumble/coupling.hpp) with t2 = the step's start, t1 = t2 - H.
/// history[0] is the sample one step back, history[1] two.
void extrapolate(std::uint32_t order, const std::vector<double>& now,
                 const std::vector<std::vector<double>>& history, std::vector<double>& coeff) {
  const std::size_t n = now.size();
  coeff.assign((order + 1) * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    coeff[i] = now[i];
    if (order == 1) coeff[n + i] = now[i] - history[0][i];
    if (order == 2) {
      const double curvature = 0.5 * (now[i] - 2.0 * history[0][i] + history[1][i]);
      coeff[n + i] = now[i] - history[0][i] + curvature;
      coeff[2 * n + i] = curvature;
    }
  }
}

/// The coupled system as a run steps it, with the vehicles at rest: the engine's vehicle/track
/// and the soil plugin itself (its own integrator, sub-steps and start of each step), fed as
/// gauss_seidel and jacobi feed them. Its deviation from the static state is what grows.
class CoupledRun {
 public:
  CoupledRun(TrackParticipant& track, SoilInstance& soil, const StabilityInputs& inputs)
      : track_(track),
        soil_(soil),
        inputs_(inputs),
        n_(track.interface_size()),
        track_dofs_(static_cast<std::size_t>(track.track_x().size())),
        vehicle_dofs_(static_cast<std::size_t>(track.vehicle_q().size())) {
    static_track_.resize(track_.state_size());
    track_.save_state(static_track_.data());
    work_.resize(static_track_.size());
    reference_track_ = static_track_;
    static_force_.resize(n_);
    track_.footprint_forces(static_force_.data());
    motion_.assign(2 * n_, 0.0);
    forces_.assign(n_, 0.0);
    soil_.motion(motion_.data(), motion_.data() + n_, n_);
    reference_motion_ = motion_;
    scale_ = 0.0;
    for (std::size_t i = 0; i < n_; ++i) scale_ = std::max(scale_, std::abs(motion_[i]));
    if (!(scale_ > 0.0)) scale_ = 1e-4;  // m: no static load (a check); a typical settlement
  }
  /// The largest static footprint settlement [m]: the perturbation's scale.
  double scale() const { return scale_; }

  /// The static state, the track's perturbed by `delta` (its state's entries after its time);
  /// the soil at rest under the static forces.
  void start(const Eigen::VectorXd& delta) {
    std::vector<double> state = static_track_;
    for (Eigen::Index j = 0; j < delta.size(); ++j)
      state[static_cast<std::size_t>(j) + 1] += delta[j];
    state[0] = 0.0;
    track_.restore_state(state.data());
    std::vector<double> u;
    soil_.initialize(0.0, static_force_, u);
    read_outputs(motion_, forces_);
    // At rest the history is the static state itself.
    motion_history_.assign(inputs_.extrapolation, motion_);
    force_history_.assign(inputs_.extrapolation, forces_);
    t_ = 0.0;
  }
  /// What deviation() measures from: the state one unperturbed macro step of the scheme leaves
  /// (the static iteration's tolerance leaves the track a little off the dynamic equilibrium,
  /// about 1e-9 of its settlement on the paper's track: a constant offset, subtracted).
  void set_reference(const std::string& scheme, double H) {
    start(Eigen::VectorXd::Zero(static_cast<Eigen::Index>(track_entries())));
    step(scheme, H);
    track_.save_state(reference_track_.data());
    read_outputs(motion_, forces_);
    reference_motion_ = motion_;
  }
  /// Entries of the track's state after its time.
  std::size_t track_entries() const { return static_track_.size() - 1; }
  /// Track entry j's weight in the norm: 1 for displacements, h for velocities, h^2 for
  /// accelerations (the track's x, v, a, then the vehicles' q, q', q'', then the footprint u and
  /// v it holds); 0 for anything after those.
  double unit_scale(std::size_t j, double h) const {
    const std::size_t nt = track_dofs_, nv = vehicle_dofs_, n = n_;
    const std::size_t blocks[] = {nt, nt, nt, nv, nv, nv, n, n};
    const double scales[] = {1.0, h, h * h, 1.0, h, h * h, 1.0, h};
    for (std::size_t b = 0; b < 8; ++b) {
      if (j < blocks[b]) return scales[b];
      j -= blocks[b];
    }
    return 0.0;
  }
  /// The deviation from the static state [m]: the track's (weighted as unit_scale) and the
  /// soil's footprint motion (u, and v times h).
  double deviation(double h) {
    track_.save_state(work_.data());
    double sum = 0.0;
    for (std::size_t j = 0; j < track_entries(); ++j) {
      const double d = (work_[j + 1] - reference_track_[j + 1]) * unit_scale(j, h);
      sum += d * d;
    }
    read_outputs(motion_, forces_);
    for (std::size_t i = 0; i < n_; ++i) {
      const double du = motion_[i] - reference_motion_[i],
                   dv = h * (motion_[n_ + i] - reference_motion_[n_ + i]);
      sum += du * du + dv * dv;
    }
    return std::sqrt(sum);
  }

  /// One macro step H [s] of the scheme.
  void step(const std::string& scheme, double H) {
    read_outputs(motion_, forces_);  // both sides' outputs at the step's start
    const std::uint32_t p = inputs_.extrapolation;
    extrapolate(p, motion_, motion_history_, wave_);
    track_.set_input(rumble_waveform{p, 2 * n_, wave_.data()});
    track_.advance(t_, H);
    std::uint32_t order = p;         // of the soil's force waveform
    if (scheme == "gauss_seidel") {  // the track's new forces, held or from the old ones
      scratch_.resize(n_);
      track_.footprint_forces(scratch_.data());
      order = inputs_.interpolation;
      wave_.assign((order + 1) * n_, 0.0);
      for (std::size_t i = 0; i < n_; ++i) {
        wave_[i] = order == 0 ? scratch_[i] : forces_[i];
        if (order == 1) wave_[n_ + i] = scratch_[i] - forces_[i];
      }
    } else {  // jacobi: the forces at the step's start, extrapolated
      extrapolate(p, forces_, force_history_, wave_);
    }
    soil_.advance(t_, H, rumble_waveform{order, n_, wave_.data()});
    if (p > 0) {  // the outputs at the step's start become the newest history
      std::rotate(motion_history_.rbegin(), motion_history_.rbegin() + 1, motion_history_.rend());
      std::rotate(force_history_.rbegin(), force_history_.rbegin() + 1, force_history_.rend());
      motion_history_[0] = motion_;
      force_history_[0] = forces_;
    }
    t_ += H;
  }

 private:
  void read_outputs(std::vector<double>& motion, std::vector<double>& forces) const {
    soil_.motion(motion.data(), motion.data() + n_, n_);
    track_.footprint_forces(forces.data());
  }

  TrackParticipant& track_;
  SoilInstance& soil_;
  StabilityInputs inputs_;
  std::size_t n_, track_dofs_, vehicle_dofs_;
  double scale_ = 1e-4;                                     // m
  double t_ = 0.0;                                          // s, since the start
  std::vector<double> static_track_, work_;                 // the track's state at rest; work space
  std::vector<double> reference_track_, reference_motion_;  // set_reference()
  std::vector<double> static_force_;                        // N per footprint
  std::vector<double> motion_, forces_;  // outputs at the step's start: soil u, v [m, m/s]; F [N]
  std::vector<std::vector<double>> motion_history_, force_history_;  // 1, 2 steps back
  std::vector<double> wave_, scratch_;  // waveform coefficients; the track's new forces
};

/// The growth factor per macro step of the coupled system's dominant mode: a small random
/// perturbation of the track's static state is followed through the scheme's macro steps (the
/// soil as the run steps it), and the factor is the geometric mean of the deviation's growth
/// over the second half of the steps, stopped early where it leaves the linear range. The norm
/// weighs velocities by the micro-step h and accelerations by h^2 (all in metres).
double growth_factor(CoupledRun& coupled, const std::string& scheme, double H, double h) {
  const auto m = static_cast<Eigen::Index>(coupled.track_entries());
  Eigen::VectorXd delta(m);
  std::mt19937_64 random(2026);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  double norm = 0.0;
  for (Eigen::Index j = 0; j < m; ++j) {
    const double w = coupled.unit_scale(static_cast<std::size_t>(j), h);
    delta[j] = w > 0.0 ? uniform(random) / w : 0.0;
    norm += (delta[j] * w) * (delta[j] * w);
  }
  delta *= kStartPerturbation * coupled.scale() / std::sqrt(norm);
  coupled.set_reference(scheme, H);
  coupled.start(delta);
  const double start = coupled.deviation(h);
  std::vector<double> log_deviation = {std::log(start)};  // one per step
  // The growth per step over the second half of the steps so far: exp of the least-squares
  // slope of log(deviation) against the step (two modes of close growth beat, which a ratio of
  // the ends would read at whatever phase they stop).
  const auto mean_growth = [&] {
    const std::size_t last = log_deviation.size() - 1, half = last / 2;
    if (last - half < 2) return std::exp(log_deviation[last] - log_deviation[half]);
    double sk = 0.0, sy = 0.0, skk = 0.0, sky = 0.0;
    for (std::size_t k = half; k <= last; ++k) {
      const auto x = static_cast<double>(k);
      sk += x;
      sy += log_deviation[k];
      skk += x * x;
      sky += x * log_deviation[k];
    }
    const auto n = static_cast<double>(last - half + 1);
    return std::exp((n * sky - sk * sy) / (n * skk - sk * sk));
  };
  const int first = std::max(kMinIterations, static_cast<int>(std::ceil(kMinDuration / H)));
  double previous = 0.0;
  for (int k = 1, checkpoint = first, doublings = 0;; ++k) {
    coupled.step(scheme, H);
    const double d = coupled.deviation(h);
    if (!(d > 0.0) || !std::isfinite(d)) throw RunError("stability: the perturbation vanished");
    if (d > kLargestPerturbation * coupled.scale() || d < kFloor * start)
      break;  // beyond the linear range, or down to round-off
    log_deviation.push_back(std::log(d));
    if (k < checkpoint) continue;
    const double growth = mean_growth();
    if (std::abs(growth - previous) < kSettled || doublings == kMaxDoublings) break;
    previous = growth;
    checkpoint *= 2;
    ++doublings;
  }
  return mean_growth();
}

}  // namespace

std::vector<StabilityPoint> coupling_stability(scenario::RunSpec spec,
                                               const PluginRegistry& registry,
                                               const std::vector<double>& macro_steps,
                                               const StabilityInputs& inputs, BuiltSoils* built) {
  for (scenario::VehicleSpec& v : spec.vehicles) v.speed = 0.0;  // linearized at rest
  RunComponents c = build_components(spec, registry, built);
  give_run_context(c, {});  // (no results directory: the analysis writes nothing)
  TrackParticipant& track = *c.track;
  SoilInstance& soil = *c.soil;
  track.solve_static([&](const std::vector<double>& force, std::vector<double>& u) {
    soil.initialize(0.0, force, u);
  });
  std::vector<double> force(track.interface_size()), u;
  track.footprint_forces(force.data());
  soil.initialize(0.0, force, u);
  CoupledRun coupled(track, soil, inputs);
  std::vector<StabilityPoint> out;
  for (double H : macro_steps)
    for (const char* scheme : {"gauss_seidel", "jacobi"})
      out.push_back({scheme, H, growth_factor(coupled, scheme, H, H / track.micro_steps(H)),
                     coupled.track_entries() + 2 * track.interface_size()});
  return out;
}

}  // namespace rumble
