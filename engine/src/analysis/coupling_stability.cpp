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

/// The coupled state at a macro-step boundary and one explicit macro step of it.
class CoupledStep {
 public:
  CoupledStep(TrackParticipant& track, IntegratedSoil& soil)
      : track_(track),
        soil_(soil),
        n_(track.interface_size()),
        track_dofs_(static_cast<std::size_t>(track.track_x().size())),
        vehicle_dofs_(static_cast<std::size_t>(track.vehicle_q().size())) {
    track_state_.resize(track_.state_size());
    track_.save_state(track_state_.data());
    soil_state_.resize(soil_.state_size());
    soil_.save_state(soil_state_.data());
    motion_.assign(2 * n_, 0.0);
    for (Eigen::VectorXd* v : {&force_, &u0_, &p_}) v->setZero(static_cast<Eigen::Index>(n_));
  }
  /// Entries of the state: the track's after its time (entry 0), then the soil's.
  std::size_t size() const { return track_state_.size() - 1 + soil_state_.size(); }
  /// Entry j's weight in the norm: 1 for displacements, h for velocities, h^2 for accelerations
  /// (the track's x, v, a, then the vehicles' q, q', q'', then the footprint u and v it holds,
  /// then the soil's x, x', x'').
  double unit_scale(std::size_t j, double h) const {
    const std::size_t nt = track_dofs_, nv = vehicle_dofs_, n = n_;
    const std::size_t blocks[] = {nt, nt, nt, nv, nv, nv, n, n};
    const double scales[] = {1.0, h, h * h, 1.0, h, h * h, 1.0, h};
    for (std::size_t b = 0; b < 8; ++b) {
      if (j < blocks[b]) return scales[b];
      j -= blocks[b];
    }
    const std::size_t ns = soil_.dof_count();
    return j < ns ? 1.0 : j < 2 * ns ? h : h * h;
  }

  /// The state after one macro step H [s] from `state` (size()).
  void step(const std::string& scheme, double H, const Eigen::VectorXd& state,
            Eigen::VectorXd& out) {
    load(state);
    const std::int64_t sub = track_.micro_steps(H);
    const double h = H / static_cast<double>(sub);
    soil_.factorize(newmark_, h);
    for (std::size_t i = 0; i < n_; ++i) {  // the soil's outputs at the step's start
      motion_[i] = soil_.footprint_u(i);
      motion_[n_ + i] = soil_.footprint_v(i);
    }
    track_.footprint_forces(force_.data());  // the track's outputs at the step's start
    track_.set_input(rumble_waveform{0, 2 * n_, motion_.data()});
    track_.advance(0.0, H);
    if (scheme == "gauss_seidel") track_.footprint_forces(force_.data());  // the new ones
    for (std::int64_t k = 0; k < sub; ++k) {
      soil_.predict(newmark_, h, u0_, p_);
      soil_.correct(newmark_, h, force_);
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
  void load(const Eigen::VectorXd& z) {
    track_state_[0] = 0.0;
    std::copy(z.data(), z.data() + track_state_.size() - 1, track_state_.begin() + 1);
    std::copy(z.data() + track_state_.size() - 1, z.data() + z.size(), soil_state_.begin());
    track_.restore_state(track_state_.data());
    soil_.restore_state(soil_state_.data());
  }
  void save(Eigen::VectorXd& z) {
    track_.save_state(track_state_.data());
    soil_.save_state(soil_state_.data());
    std::copy(track_state_.begin() + 1, track_state_.end(), z.data());
    std::copy(soil_state_.begin(), soil_state_.end(), z.data() + track_state_.size() - 1);
  }

  TrackParticipant& track_;
  IntegratedSoil& soil_;
  std::size_t n_, track_dofs_, vehicle_dofs_;
  Newmark newmark_;  // average acceleration, as the soil plugins use by default
  std::vector<double> track_state_, soil_state_, motion_;
  Eigen::VectorXd force_, u0_, p_;  // footprint forces [N]; the soil's predictors (unused)
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
                                               const std::vector<double>& macro_steps) {
  for (scenario::VehicleSpec& v : spec.vehicles) v.speed = 0.0;  // linearized at rest
  RunComponents c = build_components(spec, registry);
  std::unique_ptr<IntegratedSoil> soil = linear_soil(*c.soil, "a stability analysis");
  TrackParticipant& track = *c.track;
  track.solve_static([&](const std::vector<double>& force, std::vector<double>& u) {
    u.resize(force.size());
    soil->static_displacement(force.data(), u.data());
  });
  std::vector<double> force(track.interface_size());
  track.footprint_forces(force.data());
  soil->start_static(force.data());
  CoupledStep coupled(track, *soil);
  std::vector<StabilityPoint> out;
  for (double H : macro_steps)
    for (const char* scheme : {"gauss_seidel", "jacobi"})
      out.push_back(
          {scheme, H, growth_factor(coupled, scheme, H, H / track.micro_steps(H)), coupled.size()});
  return out;
}

}  // namespace rumble
