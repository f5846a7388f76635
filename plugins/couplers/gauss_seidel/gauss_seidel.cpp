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
// checkpoint taken at the step's start (the track's state is small; a soil advancing first is
// checkpointed only when it can be).
#include <rumble/coupling.hpp>
#include <rumble/params.hpp>
#include <rumble/plugin.hpp>

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
    return R"schema({
  "type": "object",
  "additionalProperties": false,
  "properties": {
    "order": {"enum": ["track_first", "soil_first"], "default": "track_first",
              "description": "which participant advances first in each macro step"},
    "extrapolation": {"type": "integer", "minimum": 0, "maximum": 2, "default": 0,
                      "description": "polynomial order of the first participant's input over the step, extrapolated from past macro steps (0 = held constant)"},
    "interpolation": {"type": "integer", "minimum": 0, "maximum": 1, "default": 0,
                      "description": "polynomial order of the second participant's input over the step (0 = the first participant's new end-of-step value held; 1 = linear from its previous to its new value)"},
    "max_step_halvings": {"type": "integer", "minimum": 0, "maximum": 20, "default": 10,
                          "description": "how many times a macro step refused by a participant (DISCARD) is halved and retried before the run stops; 0 = stop at the first refusal"}
  }
})schema";
  }

  GaussSeidel(const std::string& params_json, const rumble::Host& /*host*/) {
    const rumble::Params p(params_json);
    track_first_ = p.get_or<std::string>("order", "track_first") == "track_first";
    extrapolation_ = p.get_or<std::uint32_t>("extrapolation", 0);
    interpolation_ = p.get_or<std::uint32_t>("interpolation", 0);
    max_halvings_ = p.get_or<int>("max_step_halvings", 10);
  }

  void run(const CosimHost& host, double t0, double t_end, double H) override {
    const std::uint32_t first = track_first_ ? CosimHost::kTrack : CosimHost::kSoil;
    const std::uint32_t second = track_first_ ? CosimHost::kSoil : CosimHost::kTrack;
    Scheme s{host,
             first,
             second,
             OutputHistory(host, first),
             OutputHistory(host, second),
             Link(host, second, first),
             Link(host, first, second),
             GroupResiduals(host, second),
             max_halvings_ > 0 && host.can_checkpoint(first)};
    s.first_history.sample(t0);
    s.second_history.sample(t0);
    s.residuals.observe(s.second_history.latest());
    report_.residuals.resize(s.residuals.groups());
    const std::size_t steps = rumble::coupling::macro_step_count(t0, t_end, H);
    for (std::size_t k = 0; k < steps; ++k) {
      step(s, rumble::coupling::macro_step_start(t0, H, k),
           rumble::coupling::macro_step_length(t0, t_end, H, k), 0);
    }
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
  };

  void step(Scheme& s, double t, double h, int halvings) {
    const CosimHost& host = s.host;
    const std::uint32_t order_first = s.second_history.extrapolate(extrapolation_, t, h, wave_);
    s.to_first.map(wave_, order_first, in_first_);
    if (s.checkpoints) host.save(s.first, kSlot);
    host.set_input(s.first, order_first, in_first_);
    if (host.advance(s.first, t, h) == RUMBLE_DISCARD) {
      check_halvings(s, t, h, halvings, s.first);
      return retry(s, t, h, halvings);
    }
    new_first_.resize(s.first_history.size());
    host.get_output(s.first, new_first_);
    const std::uint32_t order_second =
        s.first_history.interpolate(interpolation_, new_first_, wave_second_);
    s.to_second.map(wave_second_, order_second, in_second_);
    host.set_input(s.second, order_second, in_second_);
    if (host.advance(s.second, t, h) == RUMBLE_DISCARD) {
      check_halvings(s, t, h, halvings, s.second);
      if (!s.checkpoints) {
        rumble::coupling::refused_step(host, t, h, s.second,
                                       "the participant that advanced first cannot be restored");
      }
      host.restore(s.first, kSlot);
      return retry(s, t, h, halvings);
    }
    s.first_history.push(t + h, new_first_);
    s.second_history.sample(t + h);
    s.residuals.measure(wave_, order_first, s.second_history.latest(), report_.residuals.data());
    report_.t = t;
    report_.H = h;
    host.step_report(report_);
  }

  /// Stops the run when `who` refused [t, t + h] and no halving is left.
  void check_halvings(const Scheme& s, double t, double h, int halvings, std::uint32_t who) const {
    if (halvings >= max_halvings_) {
      rumble::coupling::refused_step(
          s.host, t, h, who, "max_step_halvings (" + std::to_string(max_halvings_) + ") reached");
    }
  }

  /// Takes [t, t + h] again as two halves.
  void retry(Scheme& s, double t, double h, int halvings) {
    step(s, t, 0.5 * h, halvings + 1);
    step(s, t + 0.5 * h, 0.5 * h, halvings + 1);
  }

  bool track_first_ = true;
  std::uint32_t extrapolation_ = 0;
  std::uint32_t interpolation_ = 0;
  int max_halvings_ = 10;
  std::vector<double> wave_, wave_second_, in_first_, in_second_, new_first_;
  rumble::StepReport report_;
};

}  // namespace

RUMBLE_PLUGIN("gauss_seidel", "0.2.0", GaussSeidel)
