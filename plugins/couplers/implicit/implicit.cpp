// implicit: iterative (strong) co-simulation. Every macro step [t, t + h] is taken again, from
// checkpoints of both participants saved at its start, until the interface converges:
//
//   x  = the footprint forces [N] the soil takes at t + h (the track's outputs, channel group
//        footprint_force; over the step the soil gets the waveform from the forces at t to x:
//        linear with interpolation 1, x held with 0)
//   G(x) = the soil advances under x, then the track advances under the soil's new motion
//        (footprint_displacement [m], footprint_velocity [m/s], same interpolation from their
//        values at t) and returns its forces at t + h. The coupled step is the fixed point
//        x = G(x); iteration k evaluates x~_k = G(x_k) and accelerates (acceleration.hpp:
//        constant relaxation, Aitken, IQN-ILS) to x_{k+1}.
//
// Order (Gauss-Seidel inside the iteration): "track_first" begins each step with the track
// advancing under the soil's motion extrapolated from past steps (order `extrapolation`); its
// forces are x_1, so the soil's first input comes from the track's physics, and every iteration
// after that is soil then track. "soil_first" takes x_1 extrapolated from the track's past
// forces. Either way the step ends on a track solve under the soil's last motion, so the track
// and the soil agree exactly on the motion, and on the forces to within the tolerance.
// Iterations = soil solves (track solves: the same, plus one with track_first).
//
// Convergence, per channel group, after every track solve:
//   footprint_force           |x~_k - x_k|     the track's forces against those the soil used
//   footprint_displacement,   |y_k - y_{k-1}|  the soil's motion against the motion the track
//   footprint_velocity                          used in its previous solve (or the prediction)
// absolute = the largest over the group's channels [group's unit]; relative = absolute / the
// group's largest |value| in the run so far (coupling::GroupResiduals). A group has converged
// when absolute <= absolute_tolerance[group] AND relative <= relative_tolerance; the step when
// every group has. After max_iterations the step is accepted as it is, reported not converged,
// with a warning naming the time (on_no_convergence "warn"), or the run stops ("stop").
//
// Each step also reports the residuals of its first iterate, the predictor, under group names
// prefixed with RUMBLE_PREDICTOR_RESIDUAL_PREFIX: the coupling error of the extrapolation, of order
// extrapolation + 1 in h, where the final residuals only say the iterations converged.
//
// A participant that refuses a step (DISCARD: state unchanged) gets it again as two halves, up
// to max_step_halvings times, the other participant restored from the step's checkpoint, as
// gauss_seidel and jacobi do. Needs save/restore of the soil (declared: rumble validate refuses a
// soil that cannot). Allocates nothing per step.
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <rumble/coupling.hpp>
#include <rumble/macro_steps.hpp>
#include <rumble/params.hpp>
#include <rumble/plugin.hpp>
#include <string>
#include <vector>

#include "acceleration.hpp"

namespace {

using rumble::CosimHost;
using rumble::GroupResidual;
using rumble::coupling::GroupResiduals;
using rumble::coupling::Link;
using rumble::coupling::OutputHistory;
using rumble_implicit::AccelerationSettings;
using rumble_implicit::Accelerator;

constexpr std::uint32_t kTrack = CosimHost::kTrack, kSoil = CosimHost::kSoil;
constexpr std::uint32_t kSlot = 0;  // both participants' checkpoint at the step's start
constexpr int kLoggedWarnings = 10;

/// "%.6g" of a number, for messages.
std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

class Implicit final : public rumble::Coupler {
 public:
  static constexpr const char* kTypeName = "implicit";
  static constexpr const char* kSummary =
      "iterative (strong) coupling: each macro step repeated from checkpoints until the interface "
      "converges, with constant, Aitken or IQN-ILS acceleration";
  static constexpr std::uint64_t kSoilNeeds = rumble::kCapSaveRestore;
  static const char* params_schema() {
    static const std::string schema = rumble::object_schema(
        {rumble::coupling::order_schema(
             "Gauss-Seidel order inside each macro step: track_first starts with the track under "
             "the soil's extrapolated motion; soil_first starts with the soil under the track's "
             "extrapolated forces"),
         R"schema("acceleration": {"enum": ["constant", "aitken", "iqn_ils"], "default": "iqn_ils",
                     "description": "how the footprint forces given to the soil are updated between iterations: constant relaxation by omega, Aitken dynamic relaxation, or interface quasi-Newton with an inverse least-squares Jacobian (IQN-ILS)"},
    "omega": {"type": "number", "exclusiveMinimum": 0, "maximum": 1, "default": 0.5,
              "description": "relaxation factor [-]: constant's factor; the first factor of aitken in each macro step (at most the last step's); iqn_ils's factor while it has no columns; (0, 1]: under-relaxation, 1 is none"},
    "max_iterations": {"type": "integer", "minimum": 1, "maximum": 1000, "default": 50,
                       "description": "iterations (soil solves) per macro step at most; a step still not converged is accepted as it is and handled by on_no_convergence; [1, 1000]: a converging step takes some 3 to 40 (docs/couplers.md)"},
    "relative_tolerance": {"type": "number", "exclusiveMinimum": 0, "maximum": 1, "default": 1e-5,
                           "description": "convergence [-]: every channel group's residual relative to its largest value so far in the run must be at most this; (0, 1]: a fraction"},
    "absolute_tolerance": {
      "type": "object", "additionalProperties": false, "default": {},
      "description": "convergence: every channel group's residual (largest over its channels) must be at most this, in the group's unit, as well as within relative_tolerance",
      "properties": {
        "footprint_force": {"type": "number", "exclusiveMinimum": 0, "maximum": 1e6, "default": 1.0,
                            "description": "[N] footprint force residual; (0, 1e6] N: a footprint carries some 1e4 to 1e5 N"},
        "footprint_displacement": {"type": "number", "exclusiveMinimum": 0, "maximum": 0.01, "default": 1e-9,
                                   "description": "[m] footprint displacement change between iterations; (0, 0.01] m: a footprint settles about 1 mm"},
        "footprint_velocity": {"type": "number", "exclusiveMinimum": 0, "maximum": 1, "default": 1e-6,
                               "description": "[m/s] footprint velocity change between iterations; (0, 1] m/s: footprints move at mm/s to some 0.1 m/s"}
      }
    },
    "on_no_convergence": {"enum": ["warn", "stop"], "default": "warn",
                          "description": "a macro step not converged after max_iterations: warn (log the time and residuals, accept the step, count it in summary.json) or stop the run"})schema",
         rumble::coupling::extrapolation_schema(
             1,
             "polynomial order of the first guess of each macro step, extrapolated from past "
             "steps; "
             "it changes the iterations, not the converged result"),
         rumble::coupling::interpolation_schema(
             1,
             "inputs over the macro step: 1 = linear from the value at the step's start to the "
             "iterate at its end; 0 = the end value held over the step"),
         R"schema("reused_steps": {"type": "integer", "minimum": 0, "maximum": 100, "default": 8,
                     "description": "iqn_ils: accepted macro steps whose columns are reused in later steps (0 = none); [0, 100]: the interface changes over a train's passage; older steps say little of the next"},
    "max_columns": {"type": "integer", "minimum": 1, "maximum": 1000, "default": 100,
                    "description": "iqn_ils: columns kept at most, oldest dropped first; [1, 1000]: each costs a QR column of the interface's size"},
    "filter_epsilon": {"type": "number", "exclusiveMinimum": 0, "exclusiveMaximum": 1, "default": 1e-2,
                       "description": "iqn_ils QR filter [-]: a column whose part independent of the newer columns is below this fraction of its norm is left out; (0, 1): a fraction"})schema",
         rumble::coupling::kMaxStepHalvingsSchema});
    return schema.c_str();
  }

  Implicit(const std::string& params_json, const rumble::Host& /*host*/) {
    const rumble::Params p(params_json, params_schema());
    track_first_ = p.get<std::string>("order") == "track_first";
    acceleration_.method = rumble_implicit::method_from_name(p.get<std::string>("acceleration"));
    acceleration_.omega = p.get<double>("omega");
    acceleration_.reused_steps = p.get<std::size_t>("reused_steps");
    acceleration_.max_columns = p.get<std::size_t>("max_columns");
    acceleration_.filter_epsilon = p.get<double>("filter_epsilon");
    max_iterations_ = p.get<int>("max_iterations");
    relative_tolerance_ = p.get<double>("relative_tolerance");
    const rumble::Params absolute = p.object("absolute_tolerance");
    for (const char* group : {"footprint_force", "footprint_displacement", "footprint_velocity"})
      absolute_tolerance_[group] = absolute.get<double>(group);
    stop_unconverged_ = p.get<std::string>("on_no_convergence") == "stop";
    extrapolation_ = p.get<std::uint32_t>("extrapolation");
    interpolation_ = p.get<std::uint32_t>("interpolation");
    max_halvings_ = p.get<int>("max_step_halvings");
  }

  void run(const CosimHost& host, double t0, double t_end, double H) override {
    for (const std::uint32_t p : {kTrack, kSoil}) {
      if (!host.can_checkpoint(p)) {
        throw CosimHost::Stop(RUMBLE_ERROR,
                              "coupler 'implicit' takes every macro step several times and needs "
                              "participant '" +
                                  host.participant_name(p) +
                                  "' to save and restore its state, which it cannot; use a soil "
                                  "that can, or the gauss_seidel or jacobi coupler");
      }
    }
    Scheme s{host,
             OutputHistory(host, kTrack),
             OutputHistory(host, kSoil),
             Link(host, kSoil, kTrack),
             Link(host, kTrack, kSoil),
             GroupResiduals(host, kTrack),
             GroupResiduals(host, kSoil),
             Accelerator(acceleration_, host.output_size(kTrack)),
             {}};
    s.track.sample(t0);
    s.soil.sample(t0);
    s.track_residuals.observe(s.track.latest());
    s.soil_residuals.observe(s.soil.latest());
    const std::size_t groups = s.track_residuals.groups() + s.soil_residuals.groups();
    report_.residuals.resize(2 * groups);  // the final residuals, then the predictor's
    s.tolerance.clear();
    for (const std::uint32_t p : {kTrack, kSoil}) {
      for (const rumble::ChannelGroup& g : host.groups(p, RUMBLE_SIDE_OUTPUT)) {
        const auto it = absolute_tolerance_.find(g.name);
        s.tolerance.push_back(
            it != absolute_tolerance_.end() ? it->second : std::numeric_limits<double>::infinity());
        report_.residuals[groups + s.tolerance.size() - 1].group =
            RUMBLE_PREDICTOR_RESIDUAL_PREFIX + g.name;
      }
    }
    const std::size_t n_force = s.track.size(), n_motion = s.soil.size();
    x_.assign(n_force, 0.0);
    x_tilde_.assign(n_force, 0.0);
    x_next_.assign(n_force, 0.0);
    y_.assign(n_motion, 0.0);
    y_used_.assign(n_motion, 0.0);
    const std::size_t steps = rumble::coupling::macro_step_count(t0, t_end, H);
    for (std::size_t k = 0; k < steps; ++k) {
      step(s, rumble::coupling::macro_step_start(t0, H, k),
           rumble::coupling::macro_step_length(t0, t_end, H, k), 0);
    }
    host.free_checkpoint(kTrack, kSlot);
    host.free_checkpoint(kSoil, kSlot);
    if (unconverged_ > 0) {
      host.log(RUMBLE_LOG_WARN, std::to_string(unconverged_) + " of " + std::to_string(steps_) +
                                    " macro steps did not converge within max_iterations (" +
                                    std::to_string(max_iterations_) + ")");
    }
    if (steps_ > 0) {
      host.log(RUMBLE_LOG_INFO,
               "implicit (" + method_name() + "): " + std::to_string(steps_) + " macro steps, " +
                   number(static_cast<double>(iterations_) / steps_) +
                   " iterations per step on average, " + std::to_string(max_used_) + " at most");
    }
  }

 private:
  /// Everything one run needs, built from the host.
  struct Scheme {
    const CosimHost& host;
    OutputHistory track, soil;  // final outputs: forces [N]; displacements [m], velocities [m/s]
    Link to_track, to_soil;
    GroupResiduals track_residuals, soil_residuals;
    Accelerator accelerator;
    std::vector<double> tolerance;  // absolute, per output group: the track's then the soil's
  };

  std::string method_name() const {
    switch (acceleration_.method) {
      case rumble_implicit::Method::kConstant:
        return "constant";
      case rumble_implicit::Method::kAitken:
        return "aitken";
      case rumble_implicit::Method::kIqnIls:
        return "iqn_ils";
    }
    return "";
  }

  /// The end value (tau = 1) of a waveform over a participant's outputs.
  static void end_value(const std::vector<double>& coeff, std::uint32_t order,
                        std::vector<double>& out) {
    const std::size_t n = out.size();
    for (std::size_t i = 0; i < n; ++i) {
      double v = 0.0;
      for (std::uint32_t k = 0; k <= order; ++k) v += coeff[k * n + i];
      out[i] = v;
    }
  }

  /// Advances p over [t, t + h] under `wave` (over the other participant's outputs); false
  /// when p refused the step (DISCARD).
  bool advance(Scheme& s, std::uint32_t p, double t, double h, std::uint32_t order,
               const std::vector<double>& wave) {
    const Link& link = p == kTrack ? s.to_track : s.to_soil;
    link.map(wave, order, input_);
    s.host.set_input(p, order, input_);
    return s.host.advance(p, t, h) != RUMBLE_DISCARD;
  }

  /// Takes [t, t + h] to convergence (or max_iterations); retries it as halves when refused.
  void step(Scheme& s, double t, double h, int halvings) {
    const CosimHost& host = s.host;
    host.save(kTrack, kSlot);
    host.save(kSoil, kSlot);
    s.accelerator.begin_step(h);
    bool track_moved = false, soil_moved = false;  // advanced since the checkpoint
    std::uint32_t motion_order = 0, force_order = 0;
    // ---- the first guess
    if (track_first_) {
      const std::uint32_t order = s.soil.extrapolate(extrapolation_, t, h, wave_);
      end_value(wave_, order, y_used_);
      motion_order = s.soil.interpolate(interpolation_, y_used_, motion_wave_);
      if (!advance(s, kTrack, t, h, motion_order, motion_wave_))
        return retry(s, t, h, halvings, kTrack, track_moved, soil_moved);
      track_moved = true;
      host.get_output(kTrack, x_);
    } else {
      std::uint32_t order = s.track.extrapolate(extrapolation_, t, h, wave_);
      end_value(wave_, order, x_);
      order = s.soil.extrapolate(extrapolation_, t, h, wave_);
      end_value(wave_, order, y_used_);
    }
    // ---- iterations: the soil under x_k, then the track under the soil's motion
    int k = 1;
    bool converged = false;
    for (;; ++k) {
      if (soil_moved) host.restore(kSoil, kSlot);
      force_order = s.track.interpolate(interpolation_, x_, force_wave_);
      if (!advance(s, kSoil, t, h, force_order, force_wave_))
        return retry(s, t, h, halvings, kSoil, track_moved, soil_moved);
      soil_moved = true;
      host.get_output(kSoil, y_);
      if (track_moved) host.restore(kTrack, kSlot);
      motion_order = s.soil.interpolate(interpolation_, y_, motion_wave_);
      if (!advance(s, kTrack, t, h, motion_order, motion_wave_))
        return retry(s, t, h, halvings, kTrack, track_moved, soil_moved);
      track_moved = true;
      host.get_output(kTrack, x_tilde_);
      GroupResidual* out = report_.residuals.data();
      s.track_residuals.measure_trial(force_wave_, force_order, x_tilde_, out);
      s.soil_residuals.measure_trial(y_used_, 0, y_, out + s.track_residuals.groups());
      if (k == 1) keep_predictor_residuals(s.tolerance.size());
      converged = within_tolerance(s);
      if (converged || k >= max_iterations_) break;
      s.accelerator.next(x_, x_tilde_, x_next_);
      x_.swap(x_next_);
      std::copy(y_.begin(), y_.end(), y_used_.begin());
    }
    s.accelerator.end_step();
    // ---- the step is final
    s.track.push(t + h, x_tilde_);
    s.soil.push(t + h, y_);
    GroupResidual* out = report_.residuals.data();
    s.track_residuals.measure(force_wave_, force_order, x_tilde_, out);
    s.soil_residuals.measure(y_used_, 0, y_, out + s.track_residuals.groups());
    ++steps_;
    iterations_ += static_cast<std::uint64_t>(k);
    max_used_ = std::max(max_used_, k);
    if (!converged) unconverged(host, t, h, s.tolerance.size());
    report_.t = t;
    report_.H = h;
    report_.iterations = static_cast<std::uint32_t>(k);
    report_.converged = converged;
    host.step_report(report_);
  }

  /// The first iterate's residuals (of the `groups` groups) are the predictor's.
  void keep_predictor_residuals(std::size_t groups) {
    for (std::size_t g = 0; g < groups; ++g) {
      report_.residuals[groups + g].absolute = report_.residuals[g].absolute;
      report_.residuals[groups + g].relative = report_.residuals[g].relative;
    }
  }

  bool within_tolerance(const Scheme& s) const {
    for (std::size_t g = 0; g < s.tolerance.size(); ++g) {
      const GroupResidual& r = report_.residuals[g];
      if (!(r.absolute <= s.tolerance[g]) || !(r.relative <= relative_tolerance_)) return false;
    }
    return true;
  }

  /// A step accepted without converging: warn (the first few times) or stop.
  void unconverged(const CosimHost& host, double t, double h, std::size_t groups) {
    ++unconverged_;
    std::string m = "macro step at t = " + number(t) + " s (h = " + number(h) +
                    " s) did not converge in " + std::to_string(max_iterations_) + " iterations:";
    for (std::size_t g = 0; g < groups; ++g) {
      const GroupResidual& r = report_.residuals[g];
      m += " " + r.group + " " + number(r.absolute) + " (relative " + number(r.relative) + ")";
    }
    if (stop_unconverged_) {
      throw CosimHost::Stop(RUMBLE_ERROR, m + "; raise max_iterations, loosen the tolerances, use "
                                              "acceleration iqn_ils, or shorten time.macro_step "
                                              "(on_no_convergence is \"stop\")");
    }
    if (unconverged_ <= kLoggedWarnings) {
      host.log(RUMBLE_LOG_WARN,
               m + "; accepted as it is" +
                   (unconverged_ == kLoggedWarnings
                        ? " (further steps that do not converge are counted, not logged)"
                        : ""));
    }
  }

  /// p refused [t, t + h]: takes it again as two halves, the other participant put back first.
  void retry(Scheme& s, double t, double h, int halvings, std::uint32_t who, bool track_moved,
             bool soil_moved) {
    rumble::coupling::require_halving_left(s.host, t, h, who, halvings, max_halvings_);
    // The participant that refused is unchanged: at the step's start (restored before it
    // advanced again, or never advanced). The other one goes back.
    if (who != kTrack && track_moved) s.host.restore(kTrack, kSlot);
    if (who != kSoil && soil_moved) s.host.restore(kSoil, kSlot);
    step(s, t, 0.5 * h, halvings + 1);
    step(s, t + 0.5 * h, 0.5 * h, halvings + 1);
  }

  bool track_first_ = true;
  AccelerationSettings acceleration_;
  int max_iterations_ = 50;
  double relative_tolerance_ = 1e-5;
  std::map<std::string, double> absolute_tolerance_;
  bool stop_unconverged_ = false;
  std::uint32_t extrapolation_ = 1, interpolation_ = 1;
  int max_halvings_ = 10;
  std::uint64_t steps_ = 0, iterations_ = 0, unconverged_ = 0;
  int max_used_ = 0;
  std::vector<double> x_, x_tilde_, x_next_;  // [N] forces: soil input, track output, next
  std::vector<double> y_, y_used_;            // soil outputs [m, m/s]; those the track used before
  std::vector<double> wave_, force_wave_, motion_wave_, input_;
  rumble::StepReport report_;
};

}  // namespace

RUMBLE_PLUGIN("implicit", "0.1.0", Implicit)
