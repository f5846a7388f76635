// gauss_seidel: the sequential (staggered) explicit co-simulation scheme of the seed paper.
// Per macro step [t, t+H], with order "track_first" (the paper's):
//   1. the vehicle/track advances with the soil's outputs extrapolated over the step from its
//      last final outputs (order 0: held constant; 1: linear; 2: quadratic, through the sample
//      times, so variable steps are exact for polynomials of that order);
//   2. the soil advances with the outputs the track just produced (interpolation 0: the new
//      end-of-step value held over the step; 1: linear from the previous to the new).
// "soil_first" swaps the roles. Not iterated: the interface error is O(H) (order 0).
// Outputs and inputs are matched by channel group name (rumble/coupling.hpp).
//
// A participant that refuses a step (DISCARD: state unchanged) gets it again as two halves, up
// to max_step_halvings times; when the second participant refuses, the first is restored from a
// checkpoint taken at the step's start, taken only when the second may refuse (ABI 1.7's
// may_refuse; a soil advancing first is checkpointed only when it can be).
//
// With "adaptive", the macro step follows the coupling error of each step: the first
// participant's extrapolated input against what the second produced, and changes only as far
// as the soil's footprint velocity allows (rumble/macro_steps.hpp).
#include <algorithm>
#include <rumble/coupling.hpp>
#include <rumble/macro_steps.hpp>
#include <rumble/params.hpp>
#include <rumble/plugin.hpp>
#include <string>

namespace {

using rumble::CosimHost;
using rumble::coupling::GroupResiduals;
using rumble::coupling::Link;
using rumble::coupling::OutputHistory;

class GaussSeidel final : public rumble::Coupler {
 public:
  static constexpr const char* kTypeName = "gauss_seidel";
  static constexpr const char* kSummary =
      "sequential explicit coupling: one participant advances first, the other follows with its "
      "new outputs";
  static const char* params_schema() {
    static const std::string schema = rumble::object_schema(
        {rumble::coupling::order_schema("which participant advances first in each macro step"),
         rumble::coupling::extrapolation_schema(
             0,
             "polynomial order of the first participant's input over the step, extrapolated "
             "from past macro steps"),
         rumble::coupling::interpolation_schema(
             0,
             "polynomial order of the second participant's input over the step (0 = the first "
             "participant's new end-of-step value held; 1 = linear from its previous to its new "
             "value)"),
         rumble::coupling::kMaxStepHalvingsSchema, rumble::coupling::kAdaptiveStepSchema});
    return schema.c_str();
  }

  GaussSeidel(const std::string& params_json, const rumble::Host& /*host*/) {
    const rumble::Params p(params_json, params_schema());
    track_first_ = p.get<std::string>("order") == "track_first";
    extrapolation_ = p.get<std::uint32_t>("extrapolation");
    interpolation_ = p.get<std::uint32_t>("interpolation");
    max_halvings_ = p.get<int>("max_step_halvings");
    adaptive_ = rumble::coupling::read_adaptive_step(p);
  }

  void run(const CosimHost& host, double t0, double t_end, double H) override {
    const std::uint32_t first = track_first_ ? CosimHost::kTrack : CosimHost::kSoil;
    const std::uint32_t second = track_first_ ? CosimHost::kSoil : CosimHost::kTrack;
    // A step above the adaptive tolerance is taken again when both participants can restore.
    const bool retakes = adaptive_.enabled() && adaptive_.retake && host.can_checkpoint(first) &&
                         host.can_checkpoint(second);
    // The first is put back when the second refuses, if that can happen (ABI 1.7).
    const bool keep_first =
        ((max_halvings_ > 0 && host.may_refuse(second)) || retakes) && host.can_checkpoint(first);
    Scheme s{host,
             first,
             second,
             OutputHistory(host, first),
             OutputHistory(host, second),
             Link(host, second, first),
             Link(host, first, second),
             GroupResiduals(host, second),
             keep_first,
             retakes,
             rumble::coupling::StepChangeLimit(host, CosimHost::kSoil, adaptive_)};
    s.first_history.sample(t0);
    s.second_history.sample(t0);
    s.residuals.observe(s.second_history.latest());
    s.change_limit.observe(s.soil_history().latest(), 0.0);
    report_.residuals.resize(s.residuals.groups());
    new_first_.resize(s.first_history.size());
    new_second_.resize(s.second_history.size());
    rumble::coupling::MacroSteps steps(t0, t_end, H, adaptive_);
    while (!steps.done()) {
      step_error_ = 0.0;
      step_order_ = extrapolation_;
      if (step(s, steps.t(), steps.h(), 0, &steps))
        steps.accept(step_error_, step_order_, s.change_limit.shortest(), s.change_limit.longest());
    }
    if (adaptive_.enabled()) rumble::coupling::log_adaptive_steps(host, steps);
    if (s.retakes) host.free_checkpoint(second, kSlot);
    if (s.checkpoints) host.free_checkpoint(first, kSlot);
  }

 private:
  static constexpr std::uint32_t kSlot = 0;

  /// Everything one run needs, built from the host.
  struct Scheme {
    const CosimHost& host;
    std::uint32_t first, second;
    OutputHistory first_history, second_history;
    Link to_first, to_second;
    GroupResiduals residuals;  // of the second participant's outputs
    bool checkpoints;          // the first participant is checkpointed at every step start
    bool retakes;              // ... and the second: a step may be taken again (adaptive)
    rumble::coupling::StepChangeLimit change_limit;  // how far an adaptive step may change

    const OutputHistory& soil_history() const {
      return first == CosimHost::kSoil ? first_history : second_history;
    }
  };

  /// Takes [t, t + h]; false when `steps` asked for it again, shorter (both participants are
  /// back at t). Sub-steps of a refused step (halvings > 0) pass no `steps`.
  bool step(Scheme& s, double t, double h, int halvings,
            rumble::coupling::MacroSteps* steps = nullptr) {
    const CosimHost& host = s.host;
    const std::uint32_t order_first = s.second_history.extrapolate(extrapolation_, t, h, wave_);
    s.to_first.map(wave_, order_first, in_first_);
    if (s.checkpoints) host.save(s.first, kSlot);
    if (s.retakes) host.save(s.second, kSlot);
    host.set_input(s.first, order_first, in_first_);
    if (host.advance(s.first, t, h) == RUMBLE_DISCARD) {
      rumble::coupling::require_halving_left(host, t, h, s.first, halvings, max_halvings_);
      return retry(s, t, h, halvings);
    }
    host.get_output(s.first, new_first_);
    const std::uint32_t order_second =
        s.first_history.interpolate(interpolation_, new_first_, wave_second_);
    s.to_second.map(wave_second_, order_second, in_second_);
    host.set_input(s.second, order_second, in_second_);
    if (host.advance(s.second, t, h) == RUMBLE_DISCARD) {
      rumble::coupling::require_halving_left(host, t, h, s.second, halvings, max_halvings_);
      if (!s.checkpoints) {
        rumble::coupling::refused_step(host, t, h, s.second,
                                       "the participant that advanced first cannot be restored");
      }
      host.restore(s.first, kSlot);
      return retry(s, t, h, halvings);
    }
    host.get_output(s.second, new_second_);
    rumble::GroupResidual* residuals = report_.residuals.data();
    if (s.retakes && steps != nullptr) {
      s.residuals.measure_trial(wave_, order_first, new_second_, residuals);
      const double error = rumble::coupling::step_error(adaptive_, residuals, s.residuals.groups());
      if (steps->retake(error, order_first)) {
        host.restore(s.first, kSlot);
        host.restore(s.second, kSlot);
        return false;
      }
    }
    s.first_history.push(t + h, new_first_);
    s.second_history.push(t + h, new_second_);
    s.change_limit.observe(s.soil_history().latest(), h);
    s.residuals.measure(wave_, order_first, s.second_history.latest(), residuals);
    // The step's coupling error: the prediction the first participant used against the second's
    // outputs, O(h^(order_first + 1)); over the halves of a refused step, the worst.
    step_error_ = std::max(
        step_error_, rumble::coupling::step_error(adaptive_, residuals, s.residuals.groups()));
    step_order_ = std::min(step_order_, order_first);
    report_.t = t;
    report_.H = h;
    host.step_report(report_);
    return true;
  }

  /// Takes [t, t + h] again as two halves.
  bool retry(Scheme& s, double t, double h, int halvings) {
    step(s, t, 0.5 * h, halvings + 1);
    step(s, t + 0.5 * h, 0.5 * h, halvings + 1);
    return true;
  }

  bool track_first_ = true;
  std::uint32_t extrapolation_ = 0;
  std::uint32_t interpolation_ = 0;
  int max_halvings_ = 10;
  rumble::coupling::AdaptiveStep adaptive_;
  double step_error_ = 0.0;       // -, of the macro step being taken (MacroSteps::accept)
  std::uint32_t step_order_ = 0;  // its extrapolation order
  std::vector<double> wave_, wave_second_, in_first_, in_second_, new_first_, new_second_;
  rumble::StepReport report_;
};

}  // namespace

RUMBLE_PLUGIN("gauss_seidel", "0.3.0", GaussSeidel)
