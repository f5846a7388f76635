// The participant interface handed to a coupler plugin (rumble_cosim_host). Every call is
// checked and timed; an exception inside a participant never crosses into the plugin: it is kept
// here, the call returns RUMBLE_ERROR, and the engine rethrows it when the coupler returns.
#pragma once

#include <rumble/abi.h>

#include <array>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "run/participant.hpp"

namespace rumble {

class CosimHostImpl {
 public:
  /// Called after each macro step; throw to stop the run (the exception is kept and rethrown).
  using StepDone = std::function<void(double t, double H, double residual)>;
  static constexpr std::uint32_t kSlots = 4;

  CosimHostImpl(Participant& track, Participant& soil, StepDone step_done);
  const rumble_cosim_host* table() const { return &table_; }
  /// Rethrows the first exception a participant or step_done raised, if any.
  void rethrow_if_failed() const;
  bool failed() const;
  Participant& participant(std::uint32_t index) const { return *participants_[index]; }

 private:
  /// Runs f; any exception is kept (the first one wins) and becomes RUMBLE_ERROR.
  template <class F>
  rumble_status guard(F&& f) {
    if (failed()) return RUMBLE_ERROR;  // a stop was requested: refuse every further call
    try {
      f();
      return RUMBLE_OK;
    } catch (...) {
      const std::lock_guard<std::mutex> lock(error_mutex_);
      if (!error_) error_ = std::current_exception();
      return RUMBLE_ERROR;
    }
  }
  static CosimHostImpl& self(void* ctx) { return *static_cast<CosimHostImpl*>(ctx); }
  Participant* checked(std::uint32_t index) const;

  std::array<Participant*, 2> participants_;
  StepDone step_done_;
  std::array<std::array<std::vector<double>, kSlots>, 2> slots_;
  rumble_cosim_host table_{};
  mutable std::mutex error_mutex_;
  std::exception_ptr error_;
};

}  // namespace rumble
