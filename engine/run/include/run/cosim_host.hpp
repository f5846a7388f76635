// The participant interface handed to a coupler plugin (rumble_cosim_host). Every call is
// checked and timed; an exception inside a participant never crosses into the plugin: it is kept
// here, the call returns RUMBLE_ERROR, and the engine rethrows it when the coupler returns. A
// participant that refuses a step (DISCARD, state unchanged) is reported to the coupler as
// DISCARD so that it can retry smaller, when its ABI has DISCARD for couplers. What a coupler
// built for an older ABI calls is filled by the adapter (plugin/abi_adapter.hpp): the host itself
// has the current entries only.
#pragma once

#include <rumble/abi.h>

#include <atomic>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "run/participant.hpp"

namespace rumble {

/// A final macro step as a coupler reported it (rumble_step_report).
struct StepOutcome {
  double t = 0.0, H = 0.0;  // [s]
  std::uint32_t iterations = 1;
  bool converged = true;
  std::vector<rumble_group_residual> residuals;  // names valid during the callback only
  std::uint64_t participants = 0;                // bit p: final for participant p; 0: all
  /// The largest relative residual of any group (the 1.0 single residual), the predictor's
  /// (RUMBLE_PREDICTOR_RESIDUAL_PREFIX) left out.
  double max_relative_residual() const;
  /// The largest relative residual of the step's predictor: the predictor groups', or, when the
  /// coupler reported none (an explicit scheme, whose final residuals are its predictor's),
  /// max_relative_residual(). Of the scheme's order in H (docs/couplers.md).
  double predictor_residual() const;
  /// The group's name without RUMBLE_PREDICTOR_RESIDUAL_PREFIX when it has it, else null.
  static const char* predicted_group(const rumble_group_residual& g);
  bool final_for(std::uint32_t participant) const {
    return participants == 0 || ((participants >> participant) & 1u) != 0;
  }
};

class CosimHostImpl {
 public:
  /// Called after each final macro step; throw to stop the run (the exception is kept and
  /// rethrown).
  using OnStep = std::function<void(const StepOutcome&)>;

  /// participants[0] is the track, [1] the soil, then the coupler's extras; footprints: the
  /// layout every soil accepted, in channel order (footprint_layout). coupler_abi_minor: the ABI
  /// minor the coupler was built for (abi::coupler_takes_discard).
  CosimHostImpl(std::vector<Participant*> participants, std::vector<rumble_footprint> footprints,
                std::uint32_t coupler_abi_minor, OnStep on_step);
  const rumble_cosim_host* table() const { return &table_; }
  /// Rethrows the first exception a participant or on_step raised, if any.
  void rethrow_if_failed() const;
  bool failed() const;
  Participant& participant(std::uint32_t index) const { return *participants_.at(index); }
  std::size_t discards() const { return discards_; }
  /// Whether two participants advanced at the same time since the last call (run/core_share.hpp).
  bool take_overlap() { return overlapped_.exchange(false, std::memory_order_relaxed); }

 private:
  /// Runs f; any exception is kept (the first one wins) and becomes RUMBLE_ERROR. A refused step
  /// becomes RUMBLE_DISCARD when allow_discard (advance) and the coupler takes DISCARD.
  template <class F>
  rumble_status guard(F&& f, bool allow_discard = false);
  static CosimHostImpl& self(void* ctx) { return *static_cast<CosimHostImpl*>(ctx); }
  /// rumble_cosim_host::step_report: records the step through on_step.
  static rumble_status report_step(void* ctx, const rumble_step_report* report);
  Participant* checked(std::uint32_t index) const;
  void fill_table();
  void fill_participant_calls();  // outputs, inputs, advance, checkpoints
  void fill_named_calls();        // participant names, channel groups, reports, checkpoint care
  void fill_layout_calls();       // the footprint layout (1.4)

  std::vector<Participant*> participants_;
  std::vector<rumble_footprint> footprints_;
  bool coupler_takes_discard_;
  OnStep on_step_;
  rumble_cosim_host table_{};
  mutable std::mutex error_mutex_;
  std::exception_ptr error_;
  std::atomic<std::size_t> discards_{0};
  std::atomic<int> advancing_{0};        // participants inside advance now
  std::atomic<bool> overlapped_{false};  // two were at once, since take_overlap()
  StepOutcome outcome_;                  // the step being reported, reused from step to step
};

}  // namespace rumble
