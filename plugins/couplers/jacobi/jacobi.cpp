// jacobi: the parallel explicit co-simulation scheme. Per macro step [t, t+H] both participants
// advance at once, on two threads (the soil on a worker thread kept for the run), each from the
// other's last final outputs extrapolated over the step (order 0: held constant; 1: linear; 2:
// quadratic, through the sample times). Cheaper in wall time than Gauss-Seidel, usually less stable
// for stiff interfaces. Outputs and inputs are matched by channel group name (rumble/coupling.hpp).
//
// A refused step (DISCARD) is taken again as two halves, up to max_step_halvings times; the
// participant that did advance is restored from the checkpoint taken at the step's start. So a
// participant is checkpointed at every step start only when the other may refuse (ABI 1.7's
// may_refuse: a FEM soil of 9.6e4 DOFs copied its state in 0.1-0.15 ms of each 5-7 ms step,
// on its own thread, beside the track, which the overlap cannot spare; docs/couplers.md, "Jacobi
// on two threads"); where that participant cannot checkpoint, the other's refusal stops the run.
//
// With "adaptive", the macro step follows the coupling error of each step: each participant's
// extrapolated input against what the other produced, and changes only as far as the soil's
// footprint velocity allows (rumble/macro_steps.hpp); the soil's held force is counted in the
// soil's outputs too, where its error lands (held_input_cost.hpp).
#include <algorithm>
#include <exception>
#include <optional>
#include <rumble/coupling.hpp>
#include <rumble/macro_steps.hpp>
#include <rumble/params.hpp>
#include <rumble/plugin.hpp>
#include <string>

#include "advance_worker.hpp"
#include "held_input_cost.hpp"

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
    static const std::string schema = rumble::object_schema(
        {rumble::coupling::extrapolation_schema(
             0,
             "polynomial order of each participant's input over the step, extrapolated from past "
             "macro steps"),
         R"("threads": {"type": "integer", "minimum": 1, "maximum": 2, "default": 2,
                "description": "2: the two participants advance on two threads; 1: one after the other (same results); [1, 2]: one thread per participant"})",
         rumble::coupling::kMaxStepHalvingsSchema, rumble::coupling::kAdaptiveStepSchema});
    return schema.c_str();
  }

  Jacobi(const std::string& params_json, const rumble::Host& /*host*/) {
    const rumble::Params p(params_json, params_schema());
    extrapolation_ = p.get<std::uint32_t>("extrapolation");
    threads_ = p.get<int>("threads");
    max_halvings_ = p.get<int>("max_step_halvings");
    adaptive_ = rumble::coupling::read_adaptive_step(p);
  }

  void run(const CosimHost& host, double t0, double t_end, double H) override {
    constexpr std::uint32_t kTrack = CosimHost::kTrack, kSoil = CosimHost::kSoil;
    // A step above the adaptive tolerance is taken again when both participants can restore.
    const bool retakes = adaptive_.enabled() && adaptive_.retake && host.can_checkpoint(kTrack) &&
                         host.can_checkpoint(kSoil);
    const auto kept_for = [&](std::uint32_t p, std::uint32_t other) {
      return retakes || (max_halvings_ > 0 && host.may_refuse(other) && host.can_checkpoint(p));
    };
    Scheme s{host,
             OutputHistory(host, kTrack),
             OutputHistory(host, kSoil),
             Link(host, kSoil, kTrack),
             Link(host, kTrack, kSoil),
             GroupResiduals(host, kTrack),
             GroupResiduals(host, kSoil),
             kept_for(kTrack, kSoil),
             kept_for(kSoil, kTrack),
             retakes,
             rumble::coupling::StepChangeLimit(host, kSoil, adaptive_)};
    s.soil_cost.emplace(host, kSoil, adaptive_, host.can_checkpoint(kSoil));
    s.track.sample(t0);
    s.soil.sample(t0);
    s.change_limit.observe(s.soil.latest(), 0.0);
    s.track_residuals.observe(s.track.latest());
    s.soil_residuals.observe(s.soil.latest());
    report_.residuals.resize(s.soil_residuals.groups() + s.track_residuals.groups());
    new_track_.resize(s.track.size());
    new_soil_.resize(s.soil.size());
    if (threads_ == 2) s.soil_worker.emplace(host, kSoil);
    rumble::coupling::MacroSteps steps(t0, t_end, H, adaptive_);
    while (!steps.done()) {
      step_error_ = 0.0;
      step_order_ = extrapolation_;
      if (step(s, steps.t(), steps.h(), 0, &steps))
        steps.accept(step_error_, step_order_, s.change_limit.shortest(), s.change_limit.longest());
    }
    if (adaptive_.enabled()) {
      rumble::coupling::log_adaptive_steps(host, steps);
      host.log(RUMBLE_LOG_INFO, "held input's cost probed in " +
                                    std::to_string(s.soil_cost->advances()) +
                                    " extra soil advances");
    }
    if (s.save_track) host.free_checkpoint(kTrack, kSlot);
    if (s.save_soil || s.soil_cost->advances() > 0) host.free_checkpoint(kSoil, kSlot);
  }

 private:
  static constexpr std::uint32_t kSlot = 0;

  struct Scheme {
    const CosimHost& host;
    OutputHistory track, soil;
    Link to_track, to_soil;
    GroupResiduals track_residuals, soil_residuals;
    // Checkpointed at every step start: the track when the soil may refuse (it is put back for
    // the retry), the soil when the track may, both when a step may be retaken.
    bool save_track, save_soil, retakes;
    rumble::coupling::StepChangeLimit change_limit;  // how far an adaptive step may change
    std::optional<rumble_jacobi::AdvanceWorker> soil_worker = std::nullopt;  // with two threads
    std::optional<rumble_jacobi::HeldInputCost> soil_cost = std::nullopt;  // the soil's held force
  };

  /// Takes [t, t + h]; false when `steps` asked for it again, shorter (both participants are
  /// back at t). Sub-steps of a refused step (halvings > 0) pass no `steps`.
  bool step(Scheme& s, double t, double h, int halvings,
            rumble::coupling::MacroSteps* steps = nullptr) {
    constexpr std::uint32_t kTrack = CosimHost::kTrack, kSoil = CosimHost::kSoil;
    const CosimHost& host = s.host;
    const std::uint32_t order_track = s.soil.extrapolate(extrapolation_, t, h, from_soil_);
    const std::uint32_t order_soil = s.track.extrapolate(extrapolation_, t, h, from_track_);
    s.to_track.map(from_soil_, order_track, in_track_);
    s.to_soil.map(from_track_, order_soil, in_soil_);
    if (s.save_track) host.save(kTrack, kSlot);
    host.set_input(kTrack, order_track, in_track_);
    host.set_input(kSoil, order_soil, in_soil_);
    if (steps != nullptr) s.soil_cost->probe(t, h, order_soil, in_soil_, kSlot);
    const auto [track_status, soil_status] = advance_both(s, t, h);  // the soil saved first
    const bool track_refused = track_status == RUMBLE_DISCARD;
    const bool soil_refused = soil_status == RUMBLE_DISCARD;
    if (track_refused || soil_refused) {
      const std::uint32_t who = track_refused ? kTrack : kSoil;
      rumble::coupling::require_halving_left(host, t, h, who, halvings, max_halvings_);
      if (track_refused != soil_refused) {  // the other one advanced: take it back
        if (!(track_refused ? s.save_soil : s.save_track)) {
          rumble::coupling::refused_step(host, t, h, who,
                                         "the participant that advanced cannot be restored");
        }
        host.restore(track_refused ? kSoil : kTrack, kSlot);
      }
      step(s, t, 0.5 * h, halvings + 1);
      step(s, t + 0.5 * h, 0.5 * h, halvings + 1);
      return true;
    }
    host.get_output(kTrack, new_track_);
    host.get_output(kSoil, new_soil_);
    const std::uint32_t order = std::min(order_track, order_soil);
    s.soil_cost->finish(h, new_soil_);
    if (s.retakes && steps != nullptr &&
        steps->retake(trial_error(s, h, order_track, order_soil), order)) {
      host.restore(kTrack, kSlot);
      host.restore(kSoil, kSlot);
      return false;
    }
    s.track.push(t + h, new_track_);
    s.soil.push(t + h, new_soil_);
    s.change_limit.observe(s.soil.latest(), h);
    rumble::GroupResidual* residuals = report_.residuals.data();
    s.soil_residuals.measure(from_soil_, order_track, s.soil.latest(), residuals);
    s.track_residuals.measure(from_track_, order_soil, s.track.latest(),
                              residuals + s.soil_residuals.groups());
    // The step's coupling error: each side's prediction against the other's outputs,
    // O(h^(order + 1)); over the halves of a refused step, the worst.
    step_error_ = std::max(
        {step_error_, rumble::coupling::step_error(adaptive_, residuals, report_.residuals.size()),
         held_error(s, h)});
    step_order_ = std::min(step_order_, order);
    report_.t = t;
    report_.H = h;
    host.step_report(report_);
    return true;
  }

  /// The coupling error of the step just taken, before it is final [-]: the predictions against
  /// the new outputs (new_track_, new_soil_), as the step report will give them.
  double trial_error(const Scheme& s, double h, std::uint32_t order_track,
                     std::uint32_t order_soil) {
    rumble::GroupResidual* residuals = report_.residuals.data();
    s.soil_residuals.measure_trial(from_soil_, order_track, new_soil_, residuals);
    s.track_residuals.measure_trial(from_track_, order_soil, new_track_,
                                    residuals + s.soil_residuals.groups());
    return std::max(rumble::coupling::step_error(adaptive_, residuals, report_.residuals.size()),
                    held_error(s, h));
  }

  /// What the soil's held force cost its outputs over the step of h [-] (held_input_cost.hpp),
  /// from the residuals in report_ (the soil's groups, then the track's).
  double held_error(const Scheme& s, double h) const {
    const rumble::GroupResidual* residuals = report_.residuals.data();
    const std::size_t soil_groups = s.soil_residuals.groups();
    return s.soil_cost->error(h, residuals + soil_groups, s.track_residuals.groups(), residuals,
                              soil_groups);
  }

  /// Advances the track and the soil over [t, t + h], the soil on the worker thread when there
  /// is one, the soil checkpointed first when s.save_soil (on the worker: a large soil's copy
  /// then runs beside the track's step instead of before both); returns their statuses (OK,
  /// WARNING or DISCARD; a stop is rethrown after both have returned).
  static std::pair<rumble_status, rumble_status> advance_both(Scheme& s, double t, double h) {
    if (!s.soil_worker) {
      if (s.save_soil) s.host.save(CosimHost::kSoil, kSlot);
      return {s.host.advance(CosimHost::kTrack, t, h), s.host.advance(CosimHost::kSoil, t, h)};
    }
    s.soil_worker->start(t, h, s.save_soil, kSlot);
    rumble_status track_status = RUMBLE_OK;
    std::exception_ptr track_error;
    try {
      track_status = s.host.advance(CosimHost::kTrack, t, h);
    } catch (...) {
      track_error = std::current_exception();
    }
    const rumble_status soil_status = s.soil_worker->wait();  // rethrows the soil's stop
    if (track_error) std::rethrow_exception(track_error);
    return {track_status, soil_status};
  }

  std::uint32_t extrapolation_ = 0;
  int threads_ = 2;
  int max_halvings_ = 10;
  rumble::coupling::AdaptiveStep adaptive_;
  double step_error_ = 0.0;       // -, of the macro step being taken (MacroSteps::accept)
  std::uint32_t step_order_ = 0;  // its extrapolation order
  std::vector<double> from_soil_, from_track_, in_track_, in_soil_, new_track_, new_soil_;
  rumble::StepReport report_;
};

}  // namespace

RUMBLE_PLUGIN("jacobi", "0.3.0", Jacobi)
