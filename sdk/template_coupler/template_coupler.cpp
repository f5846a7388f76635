// template_coupler: the copy-me example of a Rumble coupler plugin (see README.md next to this
// file). Start your own with `rumble new-plugin coupler <name>`.
//
// Scheme: plain Gauss-Seidel (staggered, explicit), track first, order 0. Per macro step
// [t, t + h] [s]:
//   1. the track advances with the soil's last final outputs held constant over the step
//      (footprint displacement [m] and velocity [m/s]);
//   2. the soil advances with the footprint forces [N] the track just produced, held constant;
//   3. the step is reported final with the interface residual per soil output group: what the
//      track used against what the soil produced, relative to the group's largest value so far
//      in the run.
// Not iterated: the interface error is O(h). Channels are matched by group name through
// rumble/coupling.hpp (Link), never by position, so the scheme holds for any layout the host
// gives.
//
// A refused step (DISCARD: the participant is unchanged) is taken again as two halves, up to
// kMaxHalvings times, rather than stopping the run: a soil with a step limit of its own (an FEM
// soil, say) refuses macro steps it cannot take, and a coupler that stops at once is unusable
// with it. When the soil refuses, the track has already advanced, so it is put back from the
// checkpoint taken at the step's start. When the track cannot checkpoint, or the halvings are
// used up, the run stops with coupling::refused_step, whose message says what to change.
#include <cstddef>
#include <cstdint>
#include <rumble/coupling.hpp>
#include <rumble/plugin.hpp>
#include <string>
#include <vector>

namespace {

using rumble::CosimHost;
namespace coupling = rumble::coupling;

constexpr std::uint32_t kTrack = CosimHost::kTrack, kSoil = CosimHost::kSoil;
constexpr std::uint32_t kOrder = 0;  // track input over a step: 0 held, 1 linear, 2 quadratic
constexpr int kMaxHalvings = 10;     // a refused step is halved at most this many times
constexpr std::uint32_t kSlot = 0;   // the track's checkpoint slot (0 .. CosimHost::kSlots - 1)

/// One run: what the scheme keeps from step to step, built from the host.
class Scheme {
 public:
  Scheme(const CosimHost& host, double t0)
      : host_(host),
        soil_history_(host, kSoil),
        to_track_(host, kSoil, kTrack),
        to_soil_(host, kTrack, kSoil),
        residuals_(host, kSoil),
        // The track is kept at each step start only for a soil that may refuse (ABI 1.7).
        checkpoints_(host.can_checkpoint(kTrack) && host.may_refuse(kSoil)),
        track_output_(host.output_size(kTrack)) {
    soil_history_.sample(t0);                    // the soil's static outputs start the history...
    residuals_.observe(soil_history_.latest());  // ... and the residuals' scale
    report_.residuals.resize(residuals_.groups());
  }

  /// Macro step [t, t + h] [s], whose length has been halved `halvings` times.
  void step(double t, double h, int halvings) {
    // 1. The track, with the soil's outputs extrapolated over the step (order 0: held).
    const std::uint32_t order = soil_history_.extrapolate(kOrder, t, h, soil_wave_);
    to_track_.map(soil_wave_, order, track_input_);
    if (checkpoints_) host_.save(kTrack, kSlot);
    host_.set_input(kTrack, order, track_input_);
    if (host_.advance(kTrack, t, h) == RUMBLE_DISCARD) return retry(t, h, halvings, kTrack);
    host_.get_output(kTrack, track_output_);

    // 2. The soil, with the forces the track just produced held over the step.
    to_soil_.map(track_output_, 0, soil_input_);
    host_.set_input(kSoil, 0, soil_input_);
    if (host_.advance(kSoil, t, h) == RUMBLE_DISCARD) {
      if (!checkpoints_) {
        coupling::refused_step(host_, t, h, kSoil,
                               "the track advanced first and cannot be restored (it offers no "
                               "checkpoint)");
      }
      host_.restore(kTrack, kSlot);
      return retry(t, h, halvings, kSoil);
    }

    // 3. Final: the soil's new outputs join the history; residual of what the track used.
    soil_history_.sample(t + h);
    residuals_.measure(soil_wave_, order, soil_history_.latest(), report_.residuals.data());
    report_.t = t;
    report_.H = h;
    host_.step_report(report_);  // iterations 1, converged, final for every participant
  }

  /// After the last step: the checkpoint slot's memory goes back to the host.
  void finish() {
    if (checkpoints_) host_.free_checkpoint(kTrack, kSlot);
  }

 private:
  /// Takes [t, t + h], refused by participant `who`, again as two halves.
  void retry(double t, double h, int halvings, std::uint32_t who) {
    if (halvings >= kMaxHalvings) {
      coupling::refused_step(host_, t, h, who,
                             "halved " + std::to_string(kMaxHalvings) + " times already");
    }
    step(t, 0.5 * h, halvings + 1);
    step(t + 0.5 * h, 0.5 * h, halvings + 1);
  }

  const CosimHost& host_;
  coupling::OutputHistory soil_history_;  // the soil's final outputs, with their times
  coupling::Link to_track_, to_soil_;     // output group -> input group of the same name
  coupling::GroupResiduals residuals_;    // per soil output group
  bool checkpoints_;                      // the track is saved at every step's start
  std::vector<double> soil_wave_, track_input_, track_output_, soil_input_;
  rumble::StepReport report_;
};

class TemplateCoupler final : public rumble::Coupler {
 public:
  static constexpr const char* kTypeName = "template_coupler";
  static constexpr const char* kSummary =
      "Gauss-Seidel, order 0: track then soil, each with the other's last outputs held";
  static const char* params_schema() {
    return R"({"type": "object", "additionalProperties": false, "properties": {}})";
  }

  // No params (the schema allows none), so no rumble/params.hpp and no nlohmann_json.
  TemplateCoupler(const std::string& /*params_json*/, const rumble::Host& /*host*/) {}

  void run(const CosimHost& host, double t0, double t_end, double H) override {
    Scheme scheme(host, t0);
    // Step k starts at t0 + k H (no accumulated round-off); the last one ends exactly at t_end.
    const std::size_t steps = coupling::macro_step_count(t0, t_end, H);
    for (std::size_t k = 0; k < steps; ++k) {
      scheme.step(coupling::macro_step_start(t0, H, k),
                  coupling::macro_step_length(t0, t_end, H, k), 0);
    }
    scheme.finish();
  }
};

}  // namespace

RUMBLE_PLUGIN("template_coupler", "0.1.0", TemplateCoupler)
