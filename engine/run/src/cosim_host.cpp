#include "run/cosim_host.hpp"

#include <algorithm>
#include <chrono>
#include <string_view>

#include "core/errors.hpp"
#include "core/logging.hpp"
#include "plugin/abi_adapter.hpp"
#include "plugin/instance.hpp"
#include "run/crash_record.hpp"

namespace rumble {
namespace {

/// The coupler's log messages, at their level, in the "coupler" log.
void log_from_coupler(void*, int32_t level, const char* message) {
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
}

}  // namespace

const char* StepOutcome::predicted_group(const rumble_group_residual& g) {
  constexpr std::string_view kPrefix = RUMBLE_PREDICTOR_RESIDUAL_PREFIX;
  if (g.group == nullptr || std::string_view(g.group).substr(0, kPrefix.size()) != kPrefix)
    return nullptr;
  return g.group + kPrefix.size();
}

double StepOutcome::max_relative_residual() const {
  double r = 0.0;
  for (const rumble_group_residual& g : residuals)
    if (predicted_group(g) == nullptr) r = std::max(r, g.relative);
  return r;
}

double StepOutcome::predictor_residual() const {
  double r = -1.0;
  for (const rumble_group_residual& g : residuals)
    if (predicted_group(g) != nullptr) r = std::max(r, g.relative);
  return r >= 0.0 ? r : max_relative_residual();
}

template <class F>
rumble_status CosimHostImpl::guard(F&& f, bool allow_discard) {
  if (failed()) return RUMBLE_ERROR;  // a stop was requested: refuse every further call
  try {
    f();
    return RUMBLE_OK;
  } catch (const Discarded& e) {
    if (allow_discard && coupler_takes_discard_) {
      ++discards_;
      logger("coupler")->debug("{}", e.what());
      return RUMBLE_DISCARD;
    }
    const std::lock_guard<std::mutex> lock(error_mutex_);
    if (!error_) error_ = std::current_exception();
    return RUMBLE_ERROR;
  } catch (...) {
    const std::lock_guard<std::mutex> lock(error_mutex_);
    if (!error_) error_ = std::current_exception();
    return RUMBLE_ERROR;
  }
}

CosimHostImpl::CosimHostImpl(std::vector<Participant*> participants,
                             std::vector<rumble_footprint> footprints,
                             std::uint32_t coupler_abi_minor, OnStep on_step)
    : participants_(std::move(participants)),
      footprints_(std::move(footprints)),
      coupler_takes_discard_(abi::coupler_takes_discard(coupler_abi_minor)),
      on_step_(std::move(on_step)) {
  if (participants_.size() < 2) throw RunError("a co-simulation needs a track and a soil");
  fill_table();
}

void CosimHostImpl::fill_table() {
  table_.struct_size = sizeof(rumble_cosim_host);
  table_.ctx = this;
  fill_participant_calls();
  fill_named_calls();
  fill_layout_calls();
  table_.step_report = &CosimHostImpl::report_step;
  abi::fill_cosim_host_1_0<&CosimHostImpl::report_step>(table_);  // what a 1.0 coupler calls
}

rumble_status CosimHostImpl::report_step(void* ctx, const rumble_step_report* r) {
  return self(ctx).guard([&] {
    if (const std::string defect = abi::step_report_defect(r); !defect.empty())
      throw RunError(defect);
    StepOutcome& s = self(ctx).outcome_;  // reused: no allocation per step
    s.t = r->t;
    s.H = r->H;
    s.iterations = r->iterations;
    s.converged = r->converged != 0;
    s.participants = r->participants;
    s.residuals.assign(r->residuals, r->residuals + r->n_residuals);
    self(ctx).on_step_(s);
  });
}

void CosimHostImpl::fill_participant_calls() {
  table_.interface_size = [](void* ctx) -> uint64_t {
    return self(ctx).participants_[RUMBLE_PARTICIPANT_TRACK]->output_size();
  };
  table_.output_size = [](void* ctx, uint32_t p) -> uint64_t {
    return p < self(ctx).participants_.size() ? self(ctx).participants_[p]->output_size() : 0;
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
    CosimHostImpl& host = self(ctx);
    // A participant that starts while another is inside its advance: the coupler runs two at
    // once (the cores are shared between them, run/core_share.hpp).
    if (host.advancing_.fetch_add(1, std::memory_order_relaxed) > 0)
      host.overlapped_.store(true, std::memory_order_relaxed);
    struct Left {
      std::atomic<int>& advancing;
      ~Left() { advancing.fetch_sub(1, std::memory_order_relaxed); }
    } left{host.advancing_};
    return host.guard(
        [&] {
          Participant* part = self(ctx).checked(p);
          const auto start = std::chrono::steady_clock::now();
          const SteppingParticipant stepping(part->label().c_str());
          part->advance(t, H);
          part->wall_seconds +=
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        },
        true);
  };
  table_.save = [](void* ctx, uint32_t p, uint32_t slot) {
    return self(ctx).guard([&] { self(ctx).checked(p)->checkpoint(slot); });
  };
  table_.restore = [](void* ctx, uint32_t p, uint32_t slot) {
    return self(ctx).guard([&] { self(ctx).checked(p)->rollback(slot); });
  };
  table_.log = &log_from_coupler;
}

void CosimHostImpl::fill_named_calls() {
  table_.participant_count = [](void* ctx) -> uint32_t {
    return static_cast<uint32_t>(self(ctx).participants_.size());
  };
  table_.participant_name = [](void* ctx, uint32_t p) -> const char* {
    return p < self(ctx).participants_.size() ? self(ctx).participants_[p]->name().c_str()
                                              : nullptr;
  };
  table_.channel_groups = [](void* ctx, uint32_t p, uint32_t side, rumble_channel_group* out,
                             uint64_t capacity, uint64_t* n) {
    return self(ctx).guard([&] {
      const Participant* part = self(ctx).checked(p);
      if (side != RUMBLE_SIDE_OUTPUT && side != RUMBLE_SIDE_INPUT)
        throw RunError("coupler asked for channel groups of side " + std::to_string(side) +
                       " (0 outputs, 1 inputs)");
      const auto& groups =
          side == RUMBLE_SIDE_OUTPUT ? part->output_groups() : part->input_groups();
      *n = groups.size();
      for (std::size_t i = 0; i < groups.size() && i < capacity; ++i) out[i] = groups[i];
    });
  };
  table_.free_checkpoint = [](void* ctx, uint32_t p, uint32_t slot) {
    return self(ctx).guard([&] { self(ctx).checked(p)->free_checkpoint(slot); });
  };
  table_.can_checkpoint = [](void* ctx, uint32_t p) -> int32_t {
    int32_t can = 0;
    self(ctx).guard([&] { can = self(ctx).checked(p)->can_checkpoint() ? 1 : 0; });
    return can;
  };
  table_.may_refuse = [](void* ctx, uint32_t p) -> int32_t {
    int32_t may = 1;  // (an unknown participant: the stop's message says which)
    self(ctx).guard([&] { may = self(ctx).checked(p)->may_refuse() ? 1 : 0; });
    return may;
  };
}

void CosimHostImpl::fill_layout_calls() {
  table_.footprint_layout = [](void* ctx, rumble_footprint* out, uint64_t capacity, uint64_t* n) {
    return self(ctx).guard([&] {
      if (n == nullptr || (capacity > 0 && out == nullptr))
        throw RunError("coupler asked for the footprint layout without a count or an array");
      const std::vector<rumble_footprint>& layout = self(ctx).footprints_;
      *n = layout.size();
      std::copy_n(layout.begin(), std::min<std::size_t>(layout.size(), capacity), out);
    });
  };
}

Participant* CosimHostImpl::checked(std::uint32_t index) const {
  if (index >= participants_.size()) {
    throw RunError("coupler named participant " + std::to_string(index) + " (there are " +
                   std::to_string(participants_.size()) + ": 0.." +
                   std::to_string(participants_.size() - 1) + ")");
  }
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
