// prescribed_load: an SDK example of a coupler that applies a load of its own instead of the
// track's forces (README.md next to this file): a vertical load history P(t) [N] on one
// footprint of the soil, Lamb's problem on any soil the engine has. Built out of tree against
// the installed SDK, as `rumble new-plugin coupler` projects are.
//
// What the host has done when run() starts (docs/couplers.md, "The coupler contract"): the
// statics are solved and every participant is at its static state; get_output(track) gives the
// static footprint forces F0 [N] every soil was initialized under; each soil's input is F0, held,
// until a coupler sets another; the track's input is its static footprint motion, held. A soil's
// input is the whole footprint force, not a change from F0: a soil given P(t) alone would lose
// F0 at t0, a step unloading. So per macro step [t, t + h] [s] this coupler
//   1. from `start` on, gives the soil F0 + P e_j, linear over the step from P(t) to P(t + h)
//      (waveform order 1), e_j the footprint whose centre is nearest to `x` in the layout the
//      host gives (CosimHost::footprints(), ABI 1.4); before `start` it sets nothing and the soil
//      keeps F0; then advances the soil;
//   2. advances the track with its input untouched: it stays at its static state, its forces
//      are ignored (nothing goes from the soil to the track either);
//   3. reports the step final for both, with no interface residual (nothing is exchanged).
// The engine records what the soil took, F0 + P(t) on footprint j, in footprint_force.csv.
// A soil that refuses a step (DISCARD: unchanged) gets it again as two halves, up to
// kMaxHalvings times: the track has not moved yet, so nothing needs a checkpoint. The track
// sub-steps any step; should it refuse, the run stops with coupling::refused_step's message.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <rumble/coupling.hpp>
#include <rumble/params.hpp>
#include <rumble/plugin.hpp>
#include <string>
#include <vector>

static_assert(RUMBLE_ABI_MINOR >= 4,
              "prescribed_load reads the footprint layout, which ABI 1.4 added: build it against "
              "a Rumble SDK of ABI 1.4 or later");

namespace {

using rumble::CosimHost;
namespace coupling = rumble::coupling;

constexpr std::uint32_t kTrack = CosimHost::kTrack, kSoil = CosimHost::kSoil;
constexpr int kMaxHalvings = 10;  // a refused step is halved at most this many times

/// The vertical load P(t) [N] (down +) on the chosen footprint.
struct Load {
  double amplitude = 0.0;  // N
  bool pulse = false;      // false: a ramp to `amplitude` over `rise`, then held
  double rise = 1.0;       // s: the ramp's rise time, or the pulse's duration
  double start = 0.0;      // s: the load is 0 before

  double at(double t) const {
    const double s = t - start;  // s, since the load started
    if (s <= 0.0) return 0.0;
    if (!pulse) return amplitude * std::min(s / rise, 1.0);
    if (s >= rise) return 0.0;
    const double half_wave = std::sin(std::acos(-1.0) * s / rise);  // Hann: sin^2(pi s / rise)
    return amplitude * half_wave * half_wave;
  }
};

/// Index of the footprint whose centre is nearest to x [m] along the track.
std::size_t nearest_footprint(const std::vector<rumble::Footprint>& layout, double x) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < layout.size(); ++i)
    if (std::abs(layout[i].x - x) < std::abs(layout[best].x - x)) best = i;
  return best;
}

/// The channel of the track's output vector that carries footprint j's force: the group
/// "footprint_force" by name, never by position.
std::size_t force_channel(const CosimHost& host, std::size_t j) {
  for (const rumble::ChannelGroup& g : host.groups(kTrack, RUMBLE_SIDE_OUTPUT))
    if (g.name == "footprint_force" && j < g.count) return g.offset + j;
  throw CosimHost::Stop(RUMBLE_ERROR,
                        "the track outputs no footprint_force for footprint " + std::to_string(j));
}

/// One run: the static forces and what is reused from step to step.
class Scheme {
 public:
  Scheme(const CosimHost& host, const Load& load, std::size_t footprint)
      : host_(host),
        load_(load),
        to_soil_(host, kTrack, kSoil),
        channel_(force_channel(host, footprint)),
        static_force_(host.output_size(kTrack)) {
    host.get_output(kTrack, static_force_);  // at t0: the static forces F0 [N] (the contract)
    wave_.assign(2 * static_force_.size(), 0.0);
    std::copy(static_force_.begin(), static_force_.end(), wave_.begin());
  }

  /// Macro step [t, t + h] [s], whose length has been halved `halvings` times.
  void step(double t, double h, int halvings) {
    if (t + h > load_.start) {  // before, the soil keeps F0 held: the host's default input
      const std::size_t n = static_force_.size();
      wave_[channel_] = static_force_[channel_] + load_.at(t);  // N at tau = 0 ...
      wave_[n + channel_] = load_.at(t + h) - load_.at(t);      // ... + this x tau
      to_soil_.map(wave_, 1, soil_input_);
      host_.set_input(kSoil, 1, soil_input_);
    }
    if (host_.advance(kSoil, t, h) == RUMBLE_DISCARD) {
      if (halvings >= kMaxHalvings) {
        coupling::refused_step(host_, t, h, kSoil,
                               "halved " + std::to_string(kMaxHalvings) + " times already");
      }
      step(t, 0.5 * h, halvings + 1);
      step(t + 0.5 * h, 0.5 * h, halvings + 1);
      return;
    }
    if (host_.advance(kTrack, t, h) == RUMBLE_DISCARD) {
      coupling::refused_step(host_, t, h, kTrack,
                             "the soil has advanced and this coupler keeps no checkpoint");
    }
    report_.t = t;
    report_.H = h;
    host_.step_report(report_);  // final for both, 1 iteration, converged, no residual
  }

 private:
  const CosimHost& host_;
  Load load_;
  coupling::Link to_soil_;  // the track's output channels -> the soil's input, by group name
  std::size_t channel_;     // the loaded footprint's channel among the track's outputs
  std::vector<double> static_force_, wave_, soil_input_;  // N
  rumble::StepReport report_;
};

class PrescribedLoad final : public rumble::Coupler {
 public:
  static constexpr const char* kTypeName = "prescribed_load";
  static constexpr const char* kSummary =
      "Lamb's problem: a vertical load history on one footprint, the track's forces ignored";
  static const char* params_schema() {
    return R"({"type": "object", "additionalProperties": false, "properties": {
  "load": {"type": "number", "minimum": -1e8, "maximum": 1e8, "default": 1e4,
           "description": "the load's amplitude P [N], down + (on top of the static footprint force); [-1e8, 1e8] N: a wheel is 1e5 N, a drop weight or a vibrator some 1e4 to 1e6 N"},
  "shape": {"enum": ["ramp", "pulse"], "default": "ramp",
            "description": "ramp: from 0 to P over rise_time, then held (Lamb's step load, ramped); pulse: P sin^2(pi s / rise_time) for 0 <= s <= rise_time, s the time since start, then 0"},
  "rise_time": {"type": "number", "exclusiveMinimum": 0, "maximum": 100, "default": 5e-3,
                "description": "the ramp's rise time or the pulse's duration [s]; (0, 100] s"},
  "start": {"type": "number", "minimum": 0, "maximum": 1e6, "default": 0,
            "description": "when the load starts [s]; before it the soil keeps its static forces; [0, 1e6] s"},
  "x": {"type": "number", "minimum": -1e6, "maximum": 1e6,
        "description": "along the track [m]: the footprint whose centre is nearest is loaded; default the middle of the footprints; [-1e6, 1e6] m as vehicles' start"}}})";
  }

  PrescribedLoad(const std::string& params_json, const rumble::Host& /*host*/) {
    const rumble::Params p(params_json, params_schema(), kTypeName);
    load_.amplitude = p.get<double>("load");
    load_.pulse = p.get<std::string>("shape") == "pulse";
    load_.rise = p.get<double>("rise_time");
    load_.start = p.get<double>("start");
    if (p.has("x")) x_ = p.get<double>("x");
  }

  void run(const CosimHost& host, double t0, double t_end, double H) override {
    const std::vector<rumble::Footprint> layout = host.footprints();
    if (layout.empty()) throw CosimHost::Stop(RUMBLE_ERROR, "the track has no footprint");
    const double x = std::isnan(x_) ? 0.5 * (layout.front().x + layout.back().x) : x_;
    const std::size_t j = nearest_footprint(layout, x);
    host.log(RUMBLE_LOG_INFO,
             "prescribed_load: " + std::to_string(load_.amplitude) + " N (" +
                 (load_.pulse ? "pulse" : "ramp") + " of " + std::to_string(load_.rise) +
                 " s from t = " + std::to_string(load_.start) + " s) on footprint " +
                 std::to_string(j) + " at x = " + std::to_string(layout[j].x) +
                 " m; the track's forces are ignored");
    Scheme scheme(host, load_, j);
    const std::size_t steps = coupling::macro_step_count(t0, t_end, H);
    for (std::size_t k = 0; k < steps; ++k) {
      scheme.step(coupling::macro_step_start(t0, H, k),
                  coupling::macro_step_length(t0, t_end, H, k), 0);
    }
  }

 private:
  Load load_;
  double x_ = std::numeric_limits<double>::quiet_NaN();  // m; NaN: the middle of the layout
};

}  // namespace

RUMBLE_PLUGIN("prescribed_load", "0.1.0", PrescribedLoad)
