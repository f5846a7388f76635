#include "run/cosim_host.hpp"

#include <chrono>

#include "core/errors.hpp"
#include "core/logging.hpp"

namespace rumble {

CosimHostImpl::CosimHostImpl(Participant& track, Participant& soil, StepDone step_done)
    : participants_{&track, &soil}, step_done_(std::move(step_done)) {
  table_.struct_size = sizeof(rumble_cosim_host);
  table_.ctx = this;
  table_.interface_size = [](void* ctx) -> uint64_t {
    return self(ctx).participants_[RUMBLE_PARTICIPANT_TRACK]->output_size();
  };
  table_.output_size = [](void* ctx, uint32_t p) -> uint64_t {
    return p < 2 ? self(ctx).participants_[p]->output_size() : 0;
  };
  table_.get_output = [](void* ctx, uint32_t p, double* y, uint64_t n) {
    return self(ctx).guard([&] {
      Participant* part = self(ctx).checked(p);
      if (n != part->output_size()) {
        throw RunError("coupler asked for " + std::to_string(n) + " outputs of " + part->name() +
                       ", which has " + std::to_string(part->output_size()));
      }
      part->get_output(y);
    });
  };
  table_.set_input = [](void* ctx, uint32_t p, const rumble_waveform* u) {
    return self(ctx).guard([&] { self(ctx).checked(p)->set_input(*u); });
  };
  table_.advance = [](void* ctx, uint32_t p, double t, double H) {
    return self(ctx).guard([&] {
      Participant* part = self(ctx).checked(p);
      const auto start = std::chrono::steady_clock::now();
      part->advance(t, H);
      part->wall_seconds +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    });
  };
  table_.save = [](void* ctx, uint32_t p, uint32_t slot) {
    return self(ctx).guard([&] {
      Participant* part = self(ctx).checked(p);
      if (slot >= kSlots) throw RunError("checkpoint slot " + std::to_string(slot) + " >= 4");
      auto& buffer = self(ctx).slots_[p][slot];
      buffer.resize(part->state_size());
      part->save_state(buffer.data());
    });
  };
  table_.restore = [](void* ctx, uint32_t p, uint32_t slot) {
    return self(ctx).guard([&] {
      Participant* part = self(ctx).checked(p);
      if (slot >= kSlots || self(ctx).slots_[p][slot].empty())
        throw RunError("restore from checkpoint slot " + std::to_string(slot) + " never saved");
      part->restore_state(self(ctx).slots_[p][slot].data());
    });
  };
  table_.step_done = [](void* ctx, double t, double H, double residual) {
    return self(ctx).guard([&] { self(ctx).step_done_(t, H, residual); });
  };
  table_.log = [](void*, int32_t level, const char* message) {
    auto log = logger("coupler");
    if (level >= RUMBLE_LOG_ERROR) {
      log->error("{}", message);
    } else if (level == RUMBLE_LOG_WARN) {
      log->warn("{}", message);
    } else if (level == RUMBLE_LOG_DEBUG) {
      log->debug("{}", message);
    } else {
      log->info("{}", message);
    }
  };
}

Participant* CosimHostImpl::checked(std::uint32_t index) const {
  if (index > 1) throw RunError("coupler named participant " + std::to_string(index) + " (0 or 1)");
  return participants_[index];
}

bool CosimHostImpl::failed() const {
  const std::lock_guard<std::mutex> lock(error_mutex_);
  return static_cast<bool>(error_);
}

void CosimHostImpl::rethrow_if_failed() const {
  const std::lock_guard<std::mutex> lock(error_mutex_);
  if (error_) std::rethrow_exception(error_);
}

}  // namespace rumble
