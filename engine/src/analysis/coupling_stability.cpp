#include "analysis/coupling_stability.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "core/errors.hpp"
#include "run/run_components.hpp"
#include "track/integrated_soil.hpp"
#include "track/track_participant.hpp"

namespace rumble {
namespace {

// Size of the perturbation [m, in the weighted norm]: a thousandth of the static contact
// compression (~1e-4 m), where the Hertz law is linear to 1e-3, and far above the track's Newton
// tolerance (~1e-15 m).
constexpr double kPerturbation = 1e-7;
// Power iterations: at least this many macro steps and this much simulated time [s] (the slow
// modes of the track and soil must have settled; measured: 20 ms at H = 0.1 ms left a transient
// that read 1.0025 on stable cases); the second half is averaged.
constexpr int kMinIterations = 200;
constexpr double kMinDuration = 0.2;

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

/// Value at tau of the waveform coeff (order + 1 blocks of out.size()).
void evaluate(const std::vector<double>& coeff, std::uint32_t order, double tau,
              Eigen::VectorXd& out) {
  const auto n = static_cast<std::size_t>(out.size());
  for (std::size_t i = 0; i < n; ++i) {
    double value = 0.0, power = 1.0;
    for (std::uint32_t k = 0; k <= order; ++k, power *= tau) value += coeff[k * n + i] * power;
    out[static_cast<Eigen::Index>(i)] = value;
  }
}

/// The coupled state at a macro-step boundary and one explicit macro step of it. With inputs
/// extrapolated to order p the state also holds the p previous samples of each side's outputs
/// (the soil's footprint motion, the track's footprint forces), which the next step reads.
class CoupledStep {
 public:
  CoupledStep(TrackParticipant& track, IntegratedSoil& soil, const StabilityInputs& inputs)
      : track_(track),
        soil_(soil),
        inputs_(inputs),
        n_(track.interface_size()),
        track_dofs_(static_cast<std::size_t>(track.track_x().size())),
        vehicle_dofs_(static_cast<std::size_t>(track.vehicle_q().size())) {
    track_state_.resize(track_.state_size());
    track_.save_state(track_state_.data());
    soil_state_.resize(soil_.state_size());
    soil_.save_state(soil_state_.data());
    motion_.assign(2 * n_, 0.0);
    forces_.assign(n_, 0.0);
    for (Eigen::VectorXd* v : {&force_, &u0_, &p_}) v->setZero(static_cast<Eigen::Index>(n_));
    // At rest the history is the static state itself.
    read_outputs(motion_, forces_);
    motion_history_.assign(inputs_.extrapolation, motion_);
    force_history_.assign(inputs_.extrapolation, forces_);
    // Forces enter the norm as displacements of the soil's static secant stiffness [N/m].
    double f = 0.0, u = 0.0;
    for (std::size_t i = 0; i < n_; ++i) {
      f = std::max(f, std::abs(forces_[i]));
      u = std::max(u, std::abs(soil_.footprint_u(i)));
    }
    compliance_ = f > 0.0 && u > 0.0 ? u / f : 1.0;
  }
  /// Entries of the state: the track's after its time (entry 0), then the soil's, then the
  /// output history (p samples of the soil's u and v, p of the track's forces).
  std::size_t size() const {
    return track_state_.size() - 1 + soil_state_.size() + inputs_.extrapolation * 3 * n_;
  }
  /// Entry j's weight in the norm: 1 for displacements, h for velocities, h^2 for accelerations
  /// (the track's x, v, a, then the vehicles' q, q', q'', then the footprint u and v it holds,
  /// then the soil's x, x', x'', then the history's u, v and forces times the compliance).
  double unit_scale(std::size_t j, double h) const {
    const std::size_t nt = track_dofs_, nv = vehicle_dofs_, n = n_;
    const std::size_t blocks[] = {nt, nt, nt, nv, nv, nv, n, n};
    const double scales[] = {1.0, h, h * h, 1.0, h, h * h, 1.0, h};
    for (std::size_t b = 0; b < 8; ++b) {
      if (j < blocks[b]) return scales[b];
      j -= blocks[b];
    }
    const std::size_t ns = soil_.dof_count();
    if (j < 3 * ns) return j < ns ? 1.0 : j < 2 * ns ? h : h * h;
    j -= 3 * ns;
    const std::size_t motion_entries = inputs_.extrapolation * 2 * n;
    if (j < motion_entries) return j % (2 * n) < n ? 1.0 : h;
    return compliance_;
  }

  /// The state after one macro step H [s] from `state` (size()).
  void step(const std::string& scheme, double H, const Eigen::VectorXd& state,
            Eigen::VectorXd& out) {
    load(state);
    const std::int64_t sub = track_.micro_steps(H);
    const double h = H / static_cast<double>(sub);
    soil_.factorize(newmark_, h);
    read_outputs(motion_, forces_);  // both sides' outputs at the step's start
    const std::uint32_t p = inputs_.extrapolation;
    extrapolate(p, motion_, motion_history_, wave_);
    track_.set_input(rumble_waveform{p, 2 * n_, wave_.data()});
    track_.advance(0.0, H);
    std::uint32_t order = p;         // of the soil's force waveform
    if (scheme == "gauss_seidel") {  // the track's new forces, held or from the old ones
      std::vector<double>& next = scratch_;
      next.resize(n_);
      track_.footprint_forces(next.data());
      order = inputs_.interpolation;
      wave_.assign((order + 1) * n_, 0.0);
      for (std::size_t i = 0; i < n_; ++i) {
        wave_[i] = order == 0 ? next[i] : forces_[i];
        if (order == 1) wave_[n_ + i] = next[i] - forces_[i];
      }
    } else {  // jacobi: the forces at the step's start, extrapolated
      extrapolate(p, forces_, force_history_, wave_);
    }
    for (std::int64_t k = 0; k < sub; ++k) {
      evaluate(wave_, order, static_cast<double>(k + 1) / static_cast<double>(sub), force_);
      soil_.predict(newmark_, h, u0_, p_);
      soil_.correct(newmark_, h, force_);
    }
    if (p > 0) {  // the outputs at the step's start become the newest history
      std::rotate(motion_history_.rbegin(), motion_history_.rbegin() + 1, motion_history_.rend());
      std::rotate(force_history_.rbegin(), force_history_.rbegin() + 1, force_history_.rend());
      motion_history_[0] = motion_;
      force_history_[0] = forces_;
    }
    save(out);
  }

  Eigen::VectorXd initial() {
    Eigen::VectorXd z(static_cast<Eigen::Index>(size()));
    track_.restore_state(track_state_.data());
    soil_.restore_state(soil_state_.data());
    save(z);
    return z;
  }

 private:
  void read_outputs(std::vector<double>& motion, std::vector<double>& forces) const {
    for (std::size_t i = 0; i < n_; ++i) {
      motion[i] = soil_.footprint_u(i);
      motion[n_ + i] = soil_.footprint_v(i);
    }
    track_.footprint_forces(forces.data());
  }
  void load(const Eigen::VectorXd& z) {
    track_state_[0] = 0.0;
    const double* at = z.data();
    std::copy(at, at + track_state_.size() - 1, track_state_.begin() + 1);
    at += track_state_.size() - 1;
    std::copy(at, at + soil_state_.size(), soil_state_.begin());
    at += soil_state_.size();
    for (std::vector<double>& m : motion_history_) {
      std::copy(at, at + m.size(), m.begin());
      at += m.size();
    }
    for (std::vector<double>& f : force_history_) {
      std::copy(at, at + f.size(), f.begin());
      at += f.size();
    }
    track_.restore_state(track_state_.data());
    soil_.restore_state(soil_state_.data());
  }
  void save(Eigen::VectorXd& z) {
    track_.save_state(track_state_.data());
    soil_.save_state(soil_state_.data());
    double* at = std::copy(track_state_.begin() + 1, track_state_.end(), z.data());
    at = std::copy(soil_state_.begin(), soil_state_.end(), at);
    for (const std::vector<double>& m : motion_history_) at = std::copy(m.begin(), m.end(), at);
    for (const std::vector<double>& f : force_history_) at = std::copy(f.begin(), f.end(), at);
  }

  TrackParticipant& track_;
  IntegratedSoil& soil_;
  StabilityInputs inputs_;
  std::size_t n_, track_dofs_, vehicle_dofs_;
  double compliance_ = 1.0;  // m/N: the soil's static footprint settlement per unit force
  Newmark newmark_;          // average acceleration, as the soil plugins use by default
  std::vector<double> track_state_, soil_state_;
  std::vector<double> motion_, forces_;  // outputs at the step's start: soil u, v [m, m/s]; F [N]
  std::vector<std::vector<double>> motion_history_, force_history_;  // 1, 2 steps back
  std::vector<double> wave_, scratch_;  // waveform coefficients; the track's new forces
  Eigen::VectorXd force_, u0_, p_;      // footprint forces [N]; the soil's predictors (unused)
};

/// The growth factor per macro step of the dominant mode of the linearized map, by power
/// iteration on the scheme itself: a small perturbation of the static state is stepped and
/// renormalised every step, and the factor is the geometric mean of its growth over the second
/// half of the steps. The norm weighs velocities by the micro-step h and accelerations by
/// h^2 (all in metres), so that no unit dominates.
double growth_factor(CoupledStep& coupled, const std::string& scheme, double H, double h) {
  const Eigen::VectorXd z0 = coupled.initial();
  const auto m = static_cast<Eigen::Index>(coupled.size());
  Eigen::VectorXd base(m), next(m), delta(m), weight(m);
  coupled.step(scheme, H, z0, base);  // the static state moves by round-off: subtracted
  for (Eigen::Index j = 0; j < m; ++j)
    weight[j] = coupled.unit_scale(static_cast<std::size_t>(j), h);
  std::mt19937_64 random(2026);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (Eigen::Index j = 0; j < m; ++j) delta[j] = uniform(random) / weight[j];
  const auto norm = [&](const Eigen::VectorXd& d) { return d.cwiseProduct(weight).norm(); };
  delta *= kPerturbation / norm(delta);
  const int iterations = std::max(kMinIterations, static_cast<int>(std::ceil(kMinDuration / H)));
  double log_growth = 0.0;
  for (int k = 0; k < iterations; ++k) {
    coupled.step(scheme, H, z0 + delta, next);
    delta = next - base;
    const double g = norm(delta) / kPerturbation;
    if (!(g > 0.0) || !std::isfinite(g)) throw RunError("stability: the perturbation vanished");
    if (k >= iterations / 2) log_growth += std::log(g);
    delta *= 1.0 / g;
  }
  return std::exp(log_growth / (iterations - iterations / 2));
}

}  // namespace

std::vector<StabilityPoint> coupling_stability(scenario::RunSpec spec,
                                               const PluginRegistry& registry,
                                               const std::vector<double>& macro_steps,
                                               const StabilityInputs& inputs, BuiltSoils* built) {
  for (scenario::VehicleSpec& v : spec.vehicles) v.speed = 0.0;  // linearized at rest
  RunComponents c = build_components(spec, registry, built);
  std::unique_ptr<IntegratedSoil> soil = linear_soil(*c.soil, "a stability analysis");
  TrackParticipant& track = *c.track;
  track.solve_static([&](const std::vector<double>& force, std::vector<double>& u) {
    u.resize(force.size());
    soil->static_displacement(force.data(), u.data());
  });
  std::vector<double> force(track.interface_size());
  track.footprint_forces(force.data());
  soil->start_static(force.data());
  CoupledStep coupled(track, *soil, inputs);
  std::vector<StabilityPoint> out;
  for (double H : macro_steps)
    for (const char* scheme : {"gauss_seidel", "jacobi"})
      out.push_back(
          {scheme, H, growth_factor(coupled, scheme, H, H / track.micro_steps(H)), coupled.size()});
  return out;
}

}  // namespace rumble
