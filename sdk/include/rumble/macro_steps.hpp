// SPDX-License-Identifier: MIT
// rumble/macro_steps.hpp: the macro steps of a non-iterated coupling scheme over [t0, t_end],
// fixed or adaptive. SDK 1.3 (the adaptive error changed from 1.2's energy residual); needs
// nlohmann-json (through rumble/params.hpp).
//
// Fixed: steps of H, each start computed from its index (no drift); a final partial step ends
// exactly at t_end.
//
// Adaptive: a local-error controller on the coupling error of each step. An explicit scheme
// gives each participant an input extrapolated from past steps by a polynomial of order p (its
// "extrapolation"; 0: held); the value actually produced at the step's end differs from that
// prediction by O(h^(p+1)): the coupling's local error, which GroupResiduals measures per output
// group relative to the group's scale. The error of the step is
//   e = max over groups g of  absolute_g / max(tolerance scale_g, absolute_tolerance_g)
// (step_error()): each group's residual relative to its largest value so far in the run, with
// a floor in the group's unit, since a group that starts at rest (the footprint velocity) has
// no scale at first and would read 1 at its first moving step. The next step is the usual
// controller's for a local error of order p + 1 (docs/couplers.md, adaptive macro steps):
//   h_next = h clamp(safety (1 / e)^(1 / (p + 1)), min_change, max_change)
// within [min_step, max_step] (applied to the unrounded step) and rounded to a whole number of
// min_step, so that participants that sub-cycle at a step dividing min_step keep one sub-step
// length (no refactorisation). A step whose error is above 1 is taken again, shorter (by the
// same rule, at most 0.9 times and at least one min_step shorter), when both participants can
// be restored ("retake"); a participant's refusal (DISCARD) is retried by halving as with fixed
// steps. The time left is taken in equal whole steps of at most that step (h()), so that the
// run does not end on a short remainder; the last step may be shorter than min_step only when
// t_end is not a whole number of it from t0. Why not SDK 1.2's energy residual at the cut: it
// converges at first order whatever the scheme and is largest where the power is, not where the
// coupling errs (docs/couplers.md, adaptive macro steps).
//
// A change of step has an error of its own (appended in SDK 1.3: StepChangeLimit and
// accept(error, order, shortest, longest)): an explicit scheme lags (or leads) the coupled motion
// by about its step, so changing the step moves that lag, and the footprints, following the new
// lag over the soil's relaxation time tau (c/k of a footprint), have their velocity disturbed by
// about |v| x (the change) / tau (measured on the dip cases: tau 1.3 ms on the small Winkler
// soil, c/k 2 ms; 2.1 ms on the paper's medium soil, c/k 2.2 ms; docs/couplers.md,
// adaptive macro steps). The predictor residual does not see it (it is small exactly where the
// velocity peaks), yet it is what a peak velocity (PPV) reads, while the lag itself moves a peak
// in time, not in height. So while the footprints move, an accepted step is followed by one
// within what keeps that disturbance within kChangeShare (1/8) of the velocity's allowed error
// (StepChangeLimit); a step above the tolerance is still taken again as short as its error asks
// (accuracy first).
#ifndef RUMBLE_MACRO_STEPS_HPP
#define RUMBLE_MACRO_STEPS_HPP

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <rumble/coupling.hpp>
#include <rumble/params.hpp>
#include <sstream>
#include <stdexcept>
#include <string>

namespace rumble::coupling {

/// The "adaptive" params object of a coupler, read by read_adaptive_step() (its defaults are
/// declared once, in kAdaptiveStepObjectSchema); max_step 0: fixed steps.
struct AdaptiveStep {
  double min_step = 0.0, max_step = 0.0;      // s
  double tolerance = 0.0;                     // predictor residual / group's scale [-]
  std::map<std::string, double> absolute;     // group -> floor of the tolerance [its unit]
  double safety = 0.0;                        // -
  double min_change = 0.2, max_change = 1.5;  // per step [-]; not params
  bool retake = false;  // take a step above the tolerance again when the scheme can restore
  double relaxation_time = 0.0;  // s: over which the footprints forget a change of step (SDK 1.3,
                                 // appended; StepChangeLimit); 0: no limit
  bool enabled() const { return max_step > 0.0; }
};

/// JSON schema of the "max_step_halvings" property, for a coupler's params_schema.
inline constexpr const char* kMaxStepHalvingsSchema = R"schema("max_step_halvings": {
      "type": "integer", "minimum": 0, "maximum": 20, "default": 10,
      "description": "how many times a macro step refused by a participant (DISCARD) is halved and retried before the run stops; 0 = stop at the first refusal; [0, 20]: 20 halvings shorten the step a million times"})schema";

/// Stops the run (CosimHost::Stop) when participant `who` refused [t, t + h] after `halvings`
/// halvings and max_halvings allow no more.
inline void require_halving_left(const CosimHost& host, double t, double h, std::uint32_t who,
                                 int halvings, int max_halvings) {
  if (halvings >= max_halvings) {
    refused_step(host, t, h, who,
                 "max_step_halvings (" + std::to_string(max_halvings) + ") reached");
  }
}

/// JSON schema of the "adaptive" object (the one declaration of its parameters).
inline constexpr const char* kAdaptiveStepObjectSchema = R"schema({
  "type": "object", "additionalProperties": false, "required": ["min_step", "max_step"],
  "description": "adaptive macro step controlled by the coupling error of each step, the extrapolated input against the value produced (docs/couplers.md); time.macro_step is the first step. Absent: fixed steps of time.macro_step",
  "properties": {
    "min_step": {"type": "number", "minimum": 1e-7, "maximum": 1, "description": "shortest macro step [s]; every step is a whole number of it; [1e-7, 1] s: as time.macro_step's (usually 1e-4 to 1e-3 s; a step beyond 1 s couples none of a train's vibration)"},
    "max_step": {"type": "number", "minimum": 1e-7, "maximum": 1, "description": "longest macro step [s], >= min_step; [1e-7, 1] s: as time.macro_step's (usually 1e-4 to 1e-3 s; a step beyond 1 s couples none of a train's vibration)"},
    "tolerance": {"type": "number", "exclusiveMinimum": 0, "maximum": 1, "default": 0.01, "description": "the coupling error a step may make [-]: the largest difference, over the interface channels, between the input a participant was given (extrapolated from past steps) and the value produced at the step's end, relative to the channel group's largest value so far in the run; (0, 1]: a fraction"},
    "absolute_tolerance": {
      "type": "object", "additionalProperties": false, "default": {},
      "description": "coupling error always tolerated, per channel group in its unit, whatever the group's scale (a group at rest has none)",
      "properties": {
        "footprint_force": {"type": "number", "exclusiveMinimum": 0, "maximum": 1e6, "default": 100, "description": "[N]; (0, 1e6] N: a footprint carries some 1e4 to 1e5 N"},
        "footprint_displacement": {"type": "number", "exclusiveMinimum": 0, "maximum": 0.01, "default": 1e-7, "description": "[m]; (0, 0.01] m: a footprint settles about 1 mm and vibrates some 0.01 to 0.1 mm"},
        "footprint_velocity": {"type": "number", "exclusiveMinimum": 0, "maximum": 1, "default": 1e-3, "description": "[m/s]; (0, 1] m/s: footprints move at mm/s to some 0.1 m/s; 1e-3: 1e-4 held the step at min_step for the first ms of the dip case (docs/couplers.md)"}
      }
    },
    "relaxation_time": {"type": "number", "exclusiveMinimum": 0, "maximum": 1, "default": 1e-3, "description": "time over which the coupled footprints forget a change of macro step [s], the soil's footprint relaxation time c/k (1.0 ms on the paper's stiff soil, the default and the shortest of its soils; 2.2 ms on its medium): while the footprints move, the step changes only by what keeps the velocity it disturbs, about |v| x (change of step) / relaxation_time, within an eighth of the velocity's allowed error (tolerance x its largest value so far, at least its absolute_tolerance), so shorter is safer (docs/couplers.md); (0, 1] s: footprints relax in about 1 to 10 ms (c/k = 0.85 r0 / c_s), and 1 s all but holds the step while they move"},
    "safety": {"type": "number", "exclusiveMinimum": 0, "maximum": 1, "default": 0.9, "description": "the next step is this fraction of the step at which the error model puts the error on the tolerance [-], so that few steps are taken again; (0, 1]: a fraction"},
    "retake": {"type": "boolean", "default": true, "description": "take a step whose coupling error is above the tolerance again, shorter, when both participants can save and restore their state (false: never)"}
  }
})schema";

/// JSON schema of the "adaptive" property, for a coupler's params_schema.
inline const std::string kAdaptiveStepSchema =
    std::string(R"("adaptive": )") + kAdaptiveStepObjectSchema;

/// Reads params["adaptive"] (already validated against kAdaptiveStepSchema); throws
/// std::invalid_argument when the bounds are inverted.
inline AdaptiveStep read_adaptive_step(const Params& params) {
  AdaptiveStep a;
  if (!params.has("adaptive")) return a;
  const Params j(params.json().at("adaptive").dump(), kAdaptiveStepObjectSchema);
  a.min_step = j.get<double>("min_step");
  a.max_step = j.get<double>("max_step");
  if (!(a.min_step <= a.max_step)) {
    std::ostringstream m;
    m << "params/adaptive: min_step " << a.min_step << " s is longer than max_step " << a.max_step
      << " s; give min_step <= max_step (e.g. swap them)";
    throw std::invalid_argument(m.str());
  }
  a.tolerance = j.get<double>("tolerance");
  a.safety = j.get<double>("safety");
  a.relaxation_time = j.get<double>("relaxation_time");
  // The groups are the schema's properties of absolute_tolerance: named there alone.
  const Params absolute = j.object("absolute_tolerance");
  const nlohmann::json groups = nlohmann::json::parse(kAdaptiveStepObjectSchema)
                                    .at("properties")
                                    .at("absolute_tolerance")
                                    .at("properties");
  for (const auto& group : groups.items())
    a.absolute[group.key()] = absolute.get<double>(group.key().c_str());
  a.retake = j.get<bool>("retake");
  return a;
}

/// The error [-] (1: on the tolerance) of a step whose predictor had these n residuals: the
/// inputs the participants were given against the values produced (GroupResiduals), under the
/// adaptive step a.
inline double step_error(const AdaptiveStep& a, const GroupResidual* residuals, std::size_t n) {
  double e = 0.0;
  for (std::size_t g = 0; g < n; ++g) {
    const auto floor = a.absolute.find(residuals[g].group);
    const double allowed =
        std::max(a.tolerance * residuals[g].scale, floor != a.absolute.end() ? floor->second : 0.0);
    if (residuals[g].absolute > 0.0)
      e = std::max(e, allowed > 0.0 ? residuals[g].absolute / allowed : 1e300);
  }
  return e;
}

class MacroSteps {
 public:
  /// Steps over [t0, t_end] starting with H [s] (the only length when `adaptive` is disabled).
  MacroSteps(double t0, double t_end, double H, const AdaptiveStep& adaptive)
      : a_(adaptive),
        t0_(t0),
        t_end_(t_end),
        H_(H),
        count_(a_.enabled() ? 0 : macro_step_count(t0, t_end, H)),
        target_(a_.enabled() ? std::clamp(H, a_.min_step, a_.max_step) : H) {}

  bool done() const {
    return a_.enabled() ? t_ >= t_end_ - 1e-12 * std::max(1.0, std::abs(t_end_)) : k_ >= count_;
  }
  /// The next step [t(), t() + h()].
  double t() const { return t_; }
  double h() const {
    if (!a_.enabled()) return macro_step_length(t0_, t_end_, H_, k_);
    // The time left in equal steps of at most the target, so that the run ends on steps of the
    // length it ran at, not on a short remainder: under a force held over the step, a step much
    // shorter than the one before disturbs the footprint velocity (StepChangeLimit), and an end
    // left to chance did so by 4.6 % of the PPV (docs/couplers.md, adaptive macro steps). The
    // division changes the step by at most 1 / (steps left) of it.
    const double left = t_end_ - t_;
    const double target = rounded(target_);
    const double parts = std::ceil(left / target * (1.0 - 1e-9));
    const double h = parts > 1.0 ? rounded_up(left / parts) : target;
    return h >= left * (1.0 - 1e-9) ? left : h;
  }

  /// The step just taken is final. error [-]: its step_error(); order: the polynomial order of
  /// the extrapolation, so that the error is O(h^(order + 1)). Both steer an adaptive step
  /// (ignored for fixed steps).
  void accept(double error, std::uint32_t order) {
    const double unlimited = std::numeric_limits<double>::infinity();
    accept(error, order, -unlimited, unlimited);
  }
  /// As accept(error, order), and the next step lies within [shortest, longest] [s] where the
  /// error would take it beyond (StepChangeLimit's; SDK 1.3, appended): a growth is cut to the
  /// most whole min_steps within `longest` (at least this step), a shrink to the fewest within
  /// `shortest` (at most this step). A step above the tolerance is not accepted but taken again
  /// (retake()), as short as its error asks, whatever these bounds.
  void accept(double error, std::uint32_t order, double shortest, double longest) {
    const double h = this->h();
    ++k_;
    shortest_ = std::min(shortest_, h);
    longest_ = std::max(longest_, h);
    t_ = a_.enabled() ? t_ + h : macro_step_start(t0_, H_, k_);
    if (!a_.enabled()) return;
    error_ = error;
    // On the unrounded target: rounding alone must not hold a step that should grow.
    target_ = std::clamp(target_ * change(error_, order, a_.max_change), a_.min_step, a_.max_step);
    // A change beyond the bounds is cut, the target with it, so that a step held by them moves
    // on from where it is once the footprints come to rest.
    const double next = rounded(target_), q = a_.min_step;
    if (next > h && next > longest)
      target_ = std::max(h, std::floor(longest / q * (1.0 + 1e-9)) * q);
    else if (next < h && next < shortest)
      target_ = std::clamp(std::ceil(shortest / q * (1.0 - 1e-9)) * q, next, h);
  }

  /// Whether the step just taken (not yet accepted) is to be taken again, shorter: its error
  /// (and order, as for accept()) is above 1, retaking is on and the step can still shrink. If
  /// so, h() is now shorter.
  bool retake(double error, std::uint32_t order) {
    const double h = this->h();
    if (!a_.enabled() || !a_.retake || h <= a_.min_step * (1.0 + 1e-9)) return false;
    if (error <= 1.0) return false;
    const double shorter = h * change(error, order, 0.9);
    target_ = std::clamp(std::min(shorter, h - a_.min_step), a_.min_step, a_.max_step);
    ++retaken_;
    return true;
  }

  /// The error of the last step (1: on the tolerance), 0 before the first or for fixed steps.
  double error() const { return error_; }
  std::size_t taken() const { return k_; }
  std::size_t retaken() const { return retaken_; }
  /// s: the shortest and the longest step accepted (0 before the first).
  double shortest() const { return k_ > 0 ? shortest_ : 0.0; }
  double longest() const { return longest_; }

 private:
  AdaptiveStep a_;
  double t0_, t_end_, H_;
  std::size_t count_;  // fixed steps
  double t_ = t0_;
  std::size_t k_ = 0, retaken_ = 0;
  double target_;                            // s, before rounding to min_step
  double shortest_ = 1e300, longest_ = 0.0;  // s
  double error_ = 0.0;                       // -

  /// The step for a target [s]: the nearest whole number of min_step, at least one.
  double rounded(double target) const {
    return std::max(1.0, std::round(target / a_.min_step)) * a_.min_step;
  }
  /// The fewest whole min_steps that reach `length` [s] (at least one).
  double rounded_up(double length) const {
    return std::max(1.0, std::ceil(length / a_.min_step * (1.0 - 1e-9))) * a_.min_step;
  }

  /// Factor on the step for an error e [-] of order + 1 in h, at most `most`.
  double change(double e, std::uint32_t order, double most) const {
    if (!(e > 0.0)) return most;
    const double factor = a_.safety * std::pow(1.0 / e, 1.0 / (static_cast<double>(order) + 1.0));
    return std::clamp(factor, a_.min_change, most);
  }
};

/// Which macro steps keep the disturbance of a change of step within the tolerance while the
/// footprints move (SDK 1.3, appended). The footprints follow the scheme's lag with a delay: the
/// lag L relaxes towards the step h in use over tau (AdaptiveStep::relaxation_time),
///   L <- h + (L - h) exp(-h / tau)  after each step,
/// and a footprint moving at v is disturbed by about |v| |h' - L| / tau by a next step h' (the
/// header's comment). So h' may lie within
///   L -+ tau kChangeShare allowed / max |v|,  allowed = max(tolerance scale, floor),
/// scale: the group's largest |v| so far in the run, floor: its absolute tolerance. Measured
/// from L, not from h: a step cut short by a retake may grow back at once, the footprints having
/// had no time to follow it. Unlimited while the footprints are still, where the participant has
/// no such group, and when tau is 0 or the step is fixed.
class StepChangeLimit {
 public:
  /// The share of the velocity's allowed error a change of step may use [-]: near the smallest
  /// ratio of the PPV error to the displacement error of fixed steps (0.09 to 0.4 on the dip
  /// cases; docs/couplers.md, adaptive macro steps), so that the changes cost the peak no more
  /// than the steps do.
  static constexpr double kChangeShare = 0.125;

  /// Reads `group` (a velocity, e.g. "footprint_velocity") among the outputs of `participant`.
  StepChangeLimit(const CosimHost& host, std::uint32_t participant, const AdaptiveStep& adaptive,
                  const std::string& group = "footprint_velocity")
      : tau_(adaptive.enabled() ? adaptive.relaxation_time : 0.0), tolerance_(adaptive.tolerance) {
    for (const ChannelGroup& g : host.groups(participant, RUMBLE_SIDE_OUTPUT))
      if (g.name == group) group_ = g;
    const auto floor = adaptive.absolute.find(group);
    if (floor != adaptive.absolute.end()) floor_ = floor->second;
  }
  /// The participant's final outputs at the end of a step of h [s] (at the start: h = 0).
  void observe(const std::vector<double>& outputs, double h) {
    speed_ = 0.0;
    for (std::size_t i = group_.offset; i < group_.offset + group_.count; ++i)
      speed_ = std::max(speed_, std::abs(outputs[i]));
    scale_ = std::max(scale_, speed_);
    if (h > 0.0) lag_ = lag_ > 0.0 && tau_ > 0.0 ? h + (lag_ - h) * std::exp(-h / tau_) : h;
  }
  /// s: the shortest and the longest next step (-+ infinity when unlimited).
  double shortest() const { return lag_ - reach(); }
  double longest() const { return lag_ + reach(); }

 private:
  ChannelGroup group_;  // count 0: none
  double tau_, tolerance_, floor_ = 0.0;
  double speed_ = 0.0, scale_ = 0.0;  // [the group's unit]: the last largest |value|, the run's
  double lag_ = 0.0;                  // s: L (0 before the first step)

  double reach() const {
    if (!(tau_ > 0.0) || !(speed_ > 0.0) || !(lag_ > 0.0))
      return std::numeric_limits<double>::infinity();
    return tau_ * kChangeShare * std::max(tolerance_ * scale_, floor_) / speed_;
  }
};

/// Says at info level what an adaptive run's steps were (the engine records each one in
/// interface.csv and their range in summary.json).
inline void log_adaptive_steps(const CosimHost& host, const MacroSteps& steps) {
  std::ostringstream m;
  m << "adaptive macro step: " << steps.taken() << " steps of " << steps.shortest() << " to "
    << steps.longest() << " s, " << steps.retaken() << " taken again above the tolerance";
  host.log(RUMBLE_LOG_INFO, m.str());
}

}  // namespace rumble::coupling

#endif  // RUMBLE_MACRO_STEPS_HPP
