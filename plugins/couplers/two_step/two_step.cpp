// two_step: the classic two-step model of railway ground vibration, the seed paper's reference.
//
//   Step 1  the vehicle/track runs over the whole time span on a reduced soil (the extra
//           participant "reduced_soil": CLM, Winkler, ...), coupled to it Gauss-Seidel style
//           (track first, the reduced soil's motion extrapolated over each macro step from past
//           steps, then the reduced soil under the track's new forces). The track's footprint
//           forces [N] and the reduced soil's footprint motion are kept at every step end.
//   Step 2  the scenario's soil (the target: the FEM soil in the paper) is driven by those
//           forces alone, step by step over the same macro steps. Nothing goes back to the
//           track: the soil that the track felt is the reduced one.
//
// The track's static state is found on the reduced soil (it rests on it: "track_statics"), and
// the soil starts from the static footprint forces found.
//
// Both soils receive the forces the same way (`interpolation` 0: the step-end force held over
// the step; 1: linear from its start to its end value), so a two-step whose reduced soil equals
// the target soil reproduces step 1's soil motion exactly (a test checks this).
//
// Reports: step 1's steps are final for the track and the reduced soil (residual: the reduced
// soil's motion used by the track against the motion it produced, as in gauss_seidel); step 2's
// are final for the soil, with the two-step mismatch as residual: the target soil's footprint
// displacement and velocity against the reduced soil's at the same step end (groups
// "footprint_displacement mismatch", "footprint_velocity mismatch"; relative to the target's
// largest value so far). That mismatch is what the two-step model neglects.
//
// No step is retried: a participant that refuses a step (DISCARD) stops the run with the time
// and the fix. Needs nothing of the soils (no save/restore). Step 1's record takes
// 3 n (steps + 1) doubles, reserved once (n footprints); no allocation per step after that.
#include <rumble/coupling.hpp>
#include <rumble/params.hpp>
#include <rumble/plugin.hpp>
#include <string>
#include <vector>

namespace {

using rumble::CosimHost;
using rumble::coupling::GroupResiduals;
using rumble::coupling::Link;
using rumble::coupling::OutputHistory;

constexpr std::uint32_t kTrack = CosimHost::kTrack, kSoil = CosimHost::kSoil;
constexpr const char* kReducedSoil = "reduced_soil";

std::uint64_t bit(std::uint32_t participant) {
  return std::uint64_t{1} << participant;
}

/// Outputs of one participant at every step end of step 1, with the step-end times.
struct Record {
  std::size_t width = 0;
  std::vector<double> times;   // [s], times[0] = t0
  std::vector<double> values;  // row k: values[k * width .. (k + 1) * width - 1]

  void reserve(std::size_t steps, std::size_t w) {
    width = w;
    times.reserve(steps + 1);
    values.reserve((steps + 1) * w);
  }
  void push(double t, const std::vector<double>& y) {
    times.push_back(t);
    values.insert(values.end(), y.begin(), y.end());
  }
  const double* row(std::size_t k) const { return values.data() + k * width; }
};

class TwoStep final : public rumble::Coupler {
 public:
  static constexpr const char* kTypeName = "two_step";
  static constexpr const char* kSummary =
      "the classic two-step model: the vehicle/track on a reduced soil first, then the soil "
      "driven by the recorded footprint forces";
  static const char* params_schema() {
    static const std::string schema = rumble::object_schema(
        {rumble::coupling::extrapolation_schema(
             0,
             "step 1: polynomial order of the track's input (the reduced soil's motion) over a "
             "macro step, extrapolated from past steps"),
         rumble::coupling::interpolation_schema(
             1,
             "both steps: how a soil receives the footprint forces over a macro step (0 = the "
             "step-end force held; 1 = linear from the step-start to the step-end force)")});
    return schema.c_str();
  }
  static const char* participants_json() {
    return R"json({"reduced_soil": {"kind": "soil", "required": true, "track_statics": true,
  "description": "the soil the vehicle/track runs on in step 1 (CLM or Winkler in the paper); its footprint forces then drive the scenario's soil in step 2"}})json";
  }

  TwoStep(const std::string& params_json, const rumble::Host& /*host*/) {
    const rumble::Params p(params_json, params_schema());
    extrapolation_ = p.get<std::uint32_t>("extrapolation");
    interpolation_ = p.get<std::uint32_t>("interpolation");
  }

  void run(const CosimHost& host, double t0, double t_end, double H) override {
    const std::uint32_t reduced = host.participant(kReducedSoil);
    const std::size_t steps = rumble::coupling::macro_step_count(t0, t_end, H);
    forces_.reserve(steps, host.output_size(kTrack));
    reduced_motion_.reserve(steps, host.output_size(reduced));
    step_one(host, reduced, t0, t_end, H, steps);
    step_two(host, steps);
  }

 private:
  /// The vehicle/track on the reduced soil, Gauss-Seidel (track first), recording both sides.
  void step_one(const CosimHost& host, std::uint32_t reduced, double t0, double t_end, double H,
                std::size_t steps) {
    OutputHistory track_history(host, kTrack), soil_history(host, reduced);
    const Link to_track(host, reduced, kTrack), to_soil(host, kTrack, reduced);
    GroupResiduals residuals(host, reduced);
    track_history.sample(t0);
    soil_history.sample(t0);
    residuals.observe(soil_history.latest());
    forces_.push(t0, track_history.latest());
    reduced_motion_.push(t0, soil_history.latest());
    report_.participants = bit(kTrack) | bit(reduced);
    report_.residuals.resize(residuals.groups());
    new_forces_.resize(track_history.size());
    for (std::size_t k = 0; k < steps; ++k) {
      const double t = rumble::coupling::macro_step_start(t0, H, k);
      const double h = rumble::coupling::macro_step_length(t0, t_end, H, k);
      const std::uint32_t order_track = soil_history.extrapolate(extrapolation_, t, h, wave_);
      to_track.map(wave_, order_track, input_);
      host.set_input(kTrack, order_track, input_);
      if (host.advance(kTrack, t, h) == RUMBLE_DISCARD) refuse(host, t, h, kTrack, 1);
      host.get_output(kTrack, new_forces_);
      const std::uint32_t order_soil =
          track_history.interpolate(interpolation_, new_forces_, force_wave_);
      to_soil.map(force_wave_, order_soil, input_);
      host.set_input(reduced, order_soil, input_);
      if (host.advance(reduced, t, h) == RUMBLE_DISCARD) refuse(host, t, h, reduced, 1);
      track_history.push(t + h, new_forces_);
      soil_history.sample(t + h);
      forces_.push(t + h, new_forces_);
      reduced_motion_.push(t + h, soil_history.latest());
      residuals.measure(wave_, order_track, soil_history.latest(), report_.residuals.data());
      report_.t = t;
      report_.H = h;
      host.step_report(report_);
    }
  }

  /// The soil under the recorded forces, over the same macro steps; the mismatch with the
  /// reduced soil's motion reported.
  void step_two(const CosimHost& host, std::size_t steps) {
    const Link to_soil(host, kTrack, kSoil);
    // The mismatch compares the two soils' outputs channel by channel: both are soils on the
    // same footprints, so the host gives them the same groups (displacement, then velocity).
    GroupResiduals residuals(host, kSoil);
    const std::size_t n = forces_.width;
    std::vector<double> soil_out(host.output_size(kSoil)), reduced_out(reduced_motion_.width);
    host.get_output(kSoil, soil_out);
    residuals.observe(soil_out);
    report_.participants = bit(kSoil);
    report_.residuals.resize(residuals.groups());
    force_wave_.resize(2 * n);
    for (std::size_t k = 0; k < steps; ++k) {
      const double t = forces_.times[k], h = forces_.times[k + 1] - t;
      const double* start = forces_.row(k);
      const double* end = forces_.row(k + 1);
      const std::uint32_t order = interpolation_;
      for (std::size_t i = 0; i < n; ++i) {
        force_wave_[i] = order == 0 ? end[i] : start[i];
        if (order == 1) force_wave_[n + i] = end[i] - start[i];
      }
      to_soil.map(force_wave_, order, input_);
      host.set_input(kSoil, order, input_);
      if (host.advance(kSoil, t, h) == RUMBLE_DISCARD) refuse(host, t, h, kSoil, 2);
      host.get_output(kSoil, soil_out);
      const double* motion = reduced_motion_.row(k + 1);
      reduced_out.assign(motion, motion + reduced_out.size());
      residuals.measure(reduced_out, 0, soil_out, report_.residuals.data());
      for (rumble::GroupResidual& g : report_.residuals) g.group += " mismatch";
      report_.t = t;
      report_.H = h;
      host.step_report(report_);
    }
  }

  [[noreturn]] static void refuse(const CosimHost& host, double t, double h, std::uint32_t who,
                                  int which_step) {
    rumble::coupling::refused_step(
        host, t, h, who,
        "two_step does not retry steps (step " + std::to_string(which_step) + " of 2)");
  }

  std::uint32_t extrapolation_ = 0, interpolation_ = 1;
  Record forces_, reduced_motion_;
  std::vector<double> wave_, force_wave_, input_, new_forces_;
  rumble::StepReport report_;
};

}  // namespace

RUMBLE_PLUGIN("two_step", "0.1.0", TwoStep)
