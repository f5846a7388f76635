// jacobi: the parallel explicit co-simulation scheme. Per macro step [t, t+H] both participants
// advance at once, on two threads, each from the other's last final outputs extrapolated over
// the step (order 0: held constant; 1: linear; 2: quadratic, through the sample times).
// Cheaper in wall time than Gauss-Seidel, usually less stable for stiff interfaces. Outputs and
// inputs are matched by channel group name (rumble/coupling.hpp).
//
// A refused step (DISCARD) is taken again as two halves, up to max_step_halvings times; the
// participant that did advance is restored from the checkpoint taken at the step's start, so
// retrying needs both participants to checkpoint (otherwise a refusal stops the run).
#include <exception>
#include <rumble/coupling.hpp>
#include <rumble/params.hpp>
#include <rumble/plugin.hpp>
#include <thread>

namespace {

using rumble::CosimHost;
using rumble::coupling::GroupResiduals;
using rumble::coupling::Link;
using rumble::coupling::OutputHistory;

class Jacobi final : public rumble::Coupler {
 public:
  static constexpr const char* kTypeName = "jacobi";
  static constexpr const char* kSummary =
      "parallel explicit coupling: both participants advance at once from the previous outputs";
  /// Runs two participants at once: the host gives the soil one thread less.
  static constexpr std::uint64_t kCapabilities = rumble::kCapThreads;
  static const char* params_schema() {
    return R"schema({
  "type": "object",
  "additionalProperties": false,
  "properties": {
    "extrapolation": {"type": "integer", "minimum": 0, "maximum": 2, "default": 0,
                      "description": "polynomial order of each participant's input over the step, extrapolated from past macro steps (0 = held constant)"},
    "threads": {"type": "integer", "minimum": 1, "maximum": 2, "default": 2,
                "description": "2: the two participants advance on two threads; 1: one after the other (same results)"},
    "max_step_halvings": {"type": "integer", "minimum": 0, "maximum": 20, "default": 10,
                          "description": "how many times a macro step refused by a participant (DISCARD) is halved and retried before the run stops; 0 = stop at the first refusal"}
  }
})schema";
  }

  Jacobi(const std::string& params_json, const rumble::Host& /*host*/) {
    const rumble::Params p(params_json);
    extrapolation_ = p.get_or<std::uint32_t>("extrapolation", 0);
    threads_ = p.get_or<int>("threads", 2);
    max_halvings_ = p.get_or<int>("max_step_halvings", 10);
  }

  void run(const CosimHost& host, double t0, double t_end, double H) override {
    constexpr std::uint32_t kTrack = CosimHost::kTrack, kSoil = CosimHost::kSoil;
    Scheme s{host,
             OutputHistory(host, kTrack),
             OutputHistory(host, kSoil),
             Link(host, kSoil, kTrack),
             Link(host, kTrack, kSoil),
             GroupResiduals(host, kTrack),
             GroupResiduals(host, kSoil),
             max_halvings_ > 0 && host.can_checkpoint(kTrack) && host.can_checkpoint(kSoil)};
    s.track.sample(t0);
    s.soil.sample(t0);
    s.track_residuals.observe(s.track.latest());
    s.soil_residuals.observe(s.soil.latest());
    report_.residuals.resize(s.soil_residuals.groups() + s.track_residuals.groups());
    const std::size_t steps = rumble::coupling::macro_step_count(t0, t_end, H);
    for (std::size_t k = 0; k < steps; ++k) {
      step(s, rumble::coupling::macro_step_start(t0, H, k),
           rumble::coupling::macro_step_length(t0, t_end, H, k), 0);
    }
    if (s.checkpoints) {
      host.free_checkpoint(kTrack, kSlot);
      host.free_checkpoint(kSoil, kSlot);
    }
  }

 private:
  static constexpr std::uint32_t kSlot = 0;

  struct Scheme {
    const CosimHost& host;
    OutputHistory track, soil;
    Link to_track, to_soil;
    GroupResiduals track_residuals, soil_residuals;
    bool checkpoints;  // both participants are checkpointed at every step start
  };

  void step(Scheme& s, double t, double h, int halvings) {
    constexpr std::uint32_t kTrack = CosimHost::kTrack, kSoil = CosimHost::kSoil;
    const CosimHost& host = s.host;
    const std::uint32_t order_track = s.soil.extrapolate(extrapolation_, t, h, from_soil_);
    const std::uint32_t order_soil = s.track.extrapolate(extrapolation_, t, h, from_track_);
    s.to_track.map(from_soil_, order_track, in_track_);
    s.to_soil.map(from_track_, order_soil, in_soil_);
    if (s.checkpoints) {
      host.save(kTrack, kSlot);
      host.save(kSoil, kSlot);
    }
    host.set_input(kTrack, order_track, in_track_);
    host.set_input(kSoil, order_soil, in_soil_);
    const auto [track_status, soil_status] = advance_both(host, t, h);
    const bool track_refused = track_status == RUMBLE_DISCARD;
    const bool soil_refused = soil_status == RUMBLE_DISCARD;
    if (track_refused || soil_refused) {
      const std::uint32_t who = track_refused ? kTrack : kSoil;
      if (halvings >= max_halvings_) {
        rumble::coupling::refused_step(
            host, t, h, who, "max_step_halvings (" + std::to_string(max_halvings_) + ") reached");
      }
      if (track_refused != soil_refused) {  // the other one advanced: take it back
        if (!s.checkpoints) {
          rumble::coupling::refused_step(host, t, h, who,
                                         "the participant that advanced cannot be restored");
        }
        host.restore(track_refused ? kSoil : kTrack, kSlot);
      }
      step(s, t, 0.5 * h, halvings + 1);
      step(s, t + 0.5 * h, 0.5 * h, halvings + 1);
      return;
    }
    s.track.sample(t + h);
    s.soil.sample(t + h);
    s.soil_residuals.measure(from_soil_, order_track, s.soil.latest(), report_.residuals.data());
    s.track_residuals.measure(from_track_, order_soil, s.track.latest(),
                              report_.residuals.data() + s.soil_residuals.groups());
    report_.t = t;
    report_.H = h;
    host.step_report(report_);
  }

  /// Advances the track and the soil over [t, t + h], on two threads when asked; returns their
  /// statuses (OK, WARNING or DISCARD; a stop is rethrown after both have returned).
  std::pair<rumble_status, rumble_status> advance_both(const CosimHost& host, double t,
                                                       double h) const {
    if (threads_ != 2)
      return {host.advance(CosimHost::kTrack, t, h), host.advance(CosimHost::kSoil, t, h)};
    rumble_status soil_status = RUMBLE_OK, track_status = RUMBLE_OK;
    std::exception_ptr soil_error, track_error;
    std::thread soil_thread([&] {
      try {
        soil_status = host.advance(CosimHost::kSoil, t, h);
      } catch (...) {
        soil_error = std::current_exception();
      }
    });
    try {
      track_status = host.advance(CosimHost::kTrack, t, h);
    } catch (...) {
      track_error = std::current_exception();
    }
    soil_thread.join();
    if (track_error) std::rethrow_exception(track_error);
    if (soil_error) std::rethrow_exception(soil_error);
    return {track_status, soil_status};
  }

  std::uint32_t extrapolation_ = 0;
  int threads_ = 2;
  int max_halvings_ = 10;
  std::vector<double> from_soil_, from_track_, in_track_, in_soil_;
  rumble::StepReport report_;
};

}  // namespace

RUMBLE_PLUGIN("jacobi", "0.2.0", Jacobi)
