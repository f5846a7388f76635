// SPDX-License-Identifier: MIT
// rumble/macro_steps.hpp: the macro steps of a non-iterated coupling scheme over [t0, t_end],
// fixed or adaptive. SDK 1.2; needs nlohmann-json (through rumble/params.hpp).
//
// Fixed: steps of H, each start computed from its index (no drift); a final partial step ends
// exactly at t_end.
//
// Adaptive (the idea of ECCO, Sadjina et al., Eng. Comput. 33:607-620, 2017): after each step the
// scheme gives the step's energy residual at the cut dE [J] (rumble/cut_energy.hpp: the power
// residual of the force x velocity bond, integrated over the step) and the work through the cut
// W [J]. The error of the step is
//   e = |dE| / (h max(tolerance P_max, power_floor))
// with P_max the largest mean power W / h of any step so far in the run [W]: the residual power
// relative to the run's own scale, so a step at a turning point of the motion (W near 0) is not
// judged against nothing. A PI controller (Gustafsson's) sets the next step from e (1 is the
// tolerance) and the previous e, aiming at e = safety:
//   h_next = h clamp((safety / e)^integral_gain (e_prev / e)^proportional_gain, min_change,
//                    max_change)
// within [min_step, max_step] (applied to the unrounded step) and rounded to a whole number of
// min_step, so that participants that sub-cycle at a step dividing min_step keep one sub-step
// length (no refactorisation). A step whose error is above 1 is taken again, shorter (h safety /
// e, at least one min_step shorter), when both participants can be restored ("retake"; ECCO
// itself has no rollback, and a long step over the onset of a transient would spoil the rest of
// the run); a participant's refusal (DISCARD) is retried by halving as with fixed steps. The
// last step may be shorter than min_step, to end exactly at t_end.
#ifndef RUMBLE_MACRO_STEPS_HPP
#define RUMBLE_MACRO_STEPS_HPP

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <rumble/coupling.hpp>
#include <rumble/params.hpp>
#include <sstream>
#include <stdexcept>
#include <string>

namespace rumble::coupling {

/// The "adaptive" params object of a coupler, read by read_adaptive_step() (its defaults are
/// declared once, in kAdaptiveStepObjectSchema); max_step 0: fixed steps.
struct AdaptiveStep {
  double min_step = 0.0, max_step = 0.0;  // s
  double tolerance = 0.0;                 // energy residual / work through the cut [-]
  double power_floor = 0.0;               // W
  double safety = 0.0;                    // -
  double proportional_gain = 0.0, integral_gain = 0.0;  // -
  double min_change = 0.2, max_change = 1.5;            // per step [-]; not params
  bool retake = false;  // take a step above the tolerance again when the scheme can restore
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
  "description": "adaptive macro step controlled by the energy residual at the cut (docs/couplers.md); time.macro_step is the first step. Absent: fixed steps of time.macro_step",
  "properties": {
    "min_step": {"type": "number", "minimum": 1e-7, "maximum": 1, "description": "shortest macro step [s]; every step is a whole number of it; [1e-7, 1] s: as time.macro_step's (usually 1e-4 to 1e-3 s; a step beyond 1 s couples none of a train's vibration)"},
    "max_step": {"type": "number", "minimum": 1e-7, "maximum": 1, "description": "longest macro step [s], >= min_step; [1e-7, 1] s: as time.macro_step's (usually 1e-4 to 1e-3 s; a step beyond 1 s couples none of a train's vibration)"},
    "tolerance": {"type": "number", "exclusiveMinimum": 0, "maximum": 1, "default": 0.05, "description": "the energy residual a step may create, relative to the energy the run's strongest step passed through the cut in the same time [-]; (0, 1]: a residual as large as the energy itself is no control"},
    "power_floor": {"type": "number", "exclusiveMinimum": 0, "maximum": 1e6, "default": 0.001, "description": "residual power always tolerated [W] (before anything moves); (0, 1e6] W: a whole run passes joules through the cut (docs/couplers.md), so a megawatt tolerates any residual"},
    "safety": {"type": "number", "exclusiveMinimum": 0, "maximum": 1, "default": 0.9, "description": "the controller aims at this fraction of the tolerance [-]; (0, 1]: a fraction"},
    "proportional_gain": {"type": "number", "minimum": 0, "maximum": 1, "default": 0.2, "description": "PI controller's gain on the change of the error [-]; [0, 1]: ECCO's 0.2; above 1 the step oscillates"},
    "integral_gain": {"type": "number", "exclusiveMinimum": 0, "maximum": 1, "default": 0.15, "description": "PI controller's gain on the error [-]; (0, 1]: ECCO's 0.15; above 1 the step oscillates"},
    "retake": {"type": "boolean", "default": true, "description": "take a step whose energy residual is above the tolerance again, shorter, when both participants can save and restore their state (false: never, as ECCO)"}
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
  a.power_floor = j.get<double>("power_floor");
  a.safety = j.get<double>("safety");
  a.proportional_gain = j.get<double>("proportional_gain");
  a.integral_gain = j.get<double>("integral_gain");
  a.retake = j.get<bool>("retake");
  return a;
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
    const double left = t_end_ - t_;
    const double whole = std::max(1.0, std::round(target_ / a_.min_step));
    const double h = whole * a_.min_step;
    return h >= left * (1.0 - 1e-9) ? left : h;
  }

  /// The step just taken is final; energy_residual [J] and work [J] over it steer an adaptive
  /// step (ignored for fixed steps).
  void accept(double energy_residual, double work) {
    const double h = this->h();
    ++k_;
    shortest_ = std::min(shortest_, h);
    longest_ = std::max(longest_, h);
    t_ = a_.enabled() ? t_ + h : macro_step_start(t0_, H_, k_);
    if (!a_.enabled()) return;
    power_max_ = std::max(power_max_, work / h);
    error_ = std::abs(energy_residual) / (h * std::max(a_.tolerance * power_max_, a_.power_floor));
    double change = a_.max_change;
    if (error_ > 0.0) {
      change = std::pow(a_.safety / error_, a_.integral_gain) *
               std::pow(previous_error_ / error_, a_.proportional_gain);
      change = std::clamp(change, a_.min_change, a_.max_change);
    }
    previous_error_ = std::max(error_, 1e-10);  // a zero error must not zero the next ratio
    // On the unrounded target: rounding alone must not hold a step that should grow.
    target_ = std::clamp(target_ * change, a_.min_step, a_.max_step);
  }

  /// Whether the step just taken (not yet accepted) is to be taken again, shorter: its error is
  /// above 1, retaking is on and the step can still shrink. If so, h() is now shorter.
  bool retake(double energy_residual, double work) {
    const double h = this->h();
    if (!a_.enabled() || !a_.retake || h <= a_.min_step * (1.0 + 1e-9)) return false;
    const double power = std::max(power_max_, work / h);
    const double error =
        std::abs(energy_residual) / (h * std::max(a_.tolerance * power, a_.power_floor));
    if (error <= 1.0) return false;
    const double shorter = h * std::clamp(a_.safety / error, a_.min_change, 0.9);
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
  double target_;                              // s, before rounding to min_step
  double shortest_ = 1e300, longest_ = 0.0;    // s
  double power_max_ = 0.0;                     // W
  double error_ = 0.0, previous_error_ = 1.0;  // -
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
