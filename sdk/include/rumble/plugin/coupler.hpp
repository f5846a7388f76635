// SPDX-License-Identifier: MIT
// rumble/plugin/coupler.hpp (part of rumble/plugin.hpp): the Coupler base class and the host it
// drives (CosimHost), with the step report and its residuals.
#ifndef RUMBLE_PLUGIN_COUPLER_HPP
#define RUMBLE_PLUGIN_COUPLER_HPP

#include <rumble/abi.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <rumble/plugin/component.hpp>
#include <rumble/plugin/soil.hpp>  // Footprint
#include <stdexcept>
#include <string>
#include <vector>

namespace rumble {

/// A named group of a participant's interface channels (ABI 1.1 rumble_channel_group).
struct ChannelGroup {
  std::string name;  // e.g. "footprint_force"
  std::string unit;  // e.g. "N"
  std::size_t offset = 0, count = 0;
};

/// The interface residual of one channel group at the end of a macro step.
struct GroupResidual {
  std::string group;
  double absolute = 0.0;  // [group's unit]
  double relative = 0.0;  // absolute / the group's scale
  double scale = 0.0;     // [group's unit] (SDK 1.3; 0: none known, relative is then absolute)
};

/// What a coupler reports when a macro step is final (ABI 1.1 rumble_step_report).
struct StepReport {
  double t = 0.0, H = 0.0;  // [s]
  std::uint32_t iterations = 1;
  bool converged = true;
  std::vector<GroupResidual> residuals;
  std::uint64_t participants = 0;  // bit p: participant p's step is final; 0: every one
};

/// The host's participant interface as seen by a coupler; errors become exceptions.
class CosimHost {
 public:
  /// Thrown when the host asks the coupler to stop (Ctrl-C, plugin error): status preserved.
  class Stop : public std::runtime_error {
   public:
    Stop(rumble_status s, const std::string& what) : std::runtime_error(what), status(s) {}
    rumble_status status;
  };
  static constexpr std::uint32_t kTrack = RUMBLE_PARTICIPANT_TRACK;
  static constexpr std::uint32_t kSoil = RUMBLE_PARTICIPANT_SOIL;
  static constexpr std::uint32_t kSlots = RUMBLE_CHECKPOINT_SLOTS;

  explicit CosimHost(const rumble_cosim_host* h) : h_(h) {}
  std::size_t interface_size() const {
    return static_cast<std::size_t>(h_->interface_size(h_->ctx));
  }
  std::size_t output_size(std::uint32_t p) const {
    return static_cast<std::size_t>(h_->output_size(h_->ctx, p));
  }
  void get_output(std::uint32_t p, std::vector<double>& y) const {
    check(h_->get_output(h_->ctx, p, y.data(), y.size()), "get_output");
  }
  /// coeff: (order + 1) * channels values, see rumble_waveform.
  void set_input(std::uint32_t p, std::uint32_t order, const std::vector<double>& coeff) const {
    const rumble_waveform w{order, coeff.size() / (order + 1u), coeff.data()};
    check(h_->set_input(h_->ctx, p, &w), "set_input");
  }
  /// Returns OK, WARNING or DISCARD (the participant refused the step and is unchanged: retry
  /// smaller); ERROR/FATAL throw Stop.
  rumble_status advance(std::uint32_t p, double t, double H) const {
    return check(h_->advance(h_->ctx, p, t, H), "advance");
  }
  /// Checkpoint slot 0 .. kSlots - 1 of a participant's full state (where it is kept is the
  /// host's and the participant's business; ask can_checkpoint() first).
  void save(std::uint32_t p, std::uint32_t slot) const {
    check(h_->save(h_->ctx, p, slot), "save");
  }
  void restore(std::uint32_t p, std::uint32_t slot) const {
    check(h_->restore(h_->ctx, p, slot), "restore");
  }
  /// A final step with one residual, as ABI 1.0 couplers reported it: step_report() of one group,
  /// "interface", final for every participant. Kept so that their source still builds; new code
  /// calls step_report().
  void step_done(double t, double H, double residual) const {
    StepReport r;
    r.t = t;
    r.H = H;
    r.residuals = {{"interface", residual, residual}};
    step_report(r);
  }
  void log(rumble_log_level level, const std::string& m) const {
    h_->log(h_->ctx, level, m.c_str());
  }

  // ---- ABI 1.1 (the host is at least 1.1: a 1.1 plugin never loads into a 1.0 host)
  std::uint32_t participant_count() const { return h_->participant_count(h_->ctx); }
  std::string participant_name(std::uint32_t p) const {
    const char* name = h_->participant_name(h_->ctx, p);
    return name != nullptr ? name : "";
  }
  /// Index of the participant called name; throws Stop when there is none.
  std::uint32_t participant(const std::string& name) const {
    for (std::uint32_t p = 0; p < participant_count(); ++p)
      if (participant_name(p) == name) return p;
    throw Stop(RUMBLE_ERROR, "no participant named '" + name + "'");
  }
  /// Channel groups of a participant's outputs (RUMBLE_SIDE_OUTPUT) or inputs.
  std::vector<ChannelGroup> groups(std::uint32_t p, std::uint32_t side) const {
    std::uint64_t n = 0;
    check(h_->channel_groups(h_->ctx, p, side, nullptr, 0, &n), "channel_groups");
    std::vector<rumble_channel_group> raw(static_cast<std::size_t>(n));
    check(h_->channel_groups(h_->ctx, p, side, raw.data(), n, &n), "channel_groups");
    std::vector<ChannelGroup> out;
    for (const rumble_channel_group& g : raw)
      out.push_back(
          {g.name, g.unit, static_cast<std::size_t>(g.offset), static_cast<std::size_t>(g.count)});
    return out;
  }
  void step_report(const StepReport& r) const {
    std::vector<rumble_group_residual>& raw = residuals_;  // reused: no allocation per step
    raw.clear();
    for (const GroupResidual& g : r.residuals)
      raw.push_back({g.group.c_str(), g.absolute, g.relative});
    rumble_step_report report{};
    report.struct_size = sizeof(rumble_step_report);
    report.iterations = r.iterations;
    report.t = r.t;
    report.H = r.H;
    report.converged = r.converged ? 1 : 0;
    report.n_residuals = static_cast<std::uint32_t>(raw.size());
    report.residuals = raw.data();
    report.participants = r.participants;
    check(h_->step_report(h_->ctx, &report), "step_report");
  }
  void free_checkpoint(std::uint32_t p, std::uint32_t slot) const {
    check(h_->free_checkpoint(h_->ctx, p, slot), "free_checkpoint");
  }
  bool can_checkpoint(std::uint32_t p) const { return h_->can_checkpoint(h_->ctx, p) != 0; }
  /// ABI 1.7: whether p's advance may return DISCARD (some vehicle or soil in it does not
  /// declare kCapNeverRefuses). A participant that never refuses needs no checkpoint of the
  /// other to be put back after its refusal. True on a host older than 1.7.
  bool may_refuse(std::uint32_t p) const {
    if (!RUMBLE_HAS_FIELD(h_, rumble_cosim_host, may_refuse) || h_->may_refuse == nullptr)
      return true;
    return h_->may_refuse(h_->ctx, p) != 0;
  }

  // ---- ABI 1.4
  /// The footprints every soil accepted, in channel order: footprint i is channel i of the
  /// footprint_force [N], footprint_displacement [m] and footprint_velocity [m/s] groups (x, y
  /// of its centre [m]; length across and width along the track [m]). For a coupler that
  /// applies loads of its own (docs/couplers.md, "The coupler contract"). Throws Stop on a host
  /// that does not give it (older than ABI 1.4: such a host refuses a 1.4 coupler anyway).
  std::vector<Footprint> footprints() const {
    if (!RUMBLE_HAS_FIELD(h_, rumble_cosim_host, footprint_layout) ||
        h_->footprint_layout == nullptr)
      throw Stop(RUMBLE_ERROR, "the host gives no footprint layout (ABI 1.4 appended it)");
    std::uint64_t n = 0;
    check(h_->footprint_layout(h_->ctx, nullptr, 0, &n), "footprint_layout");
    std::vector<Footprint> out(static_cast<std::size_t>(n));
    check(h_->footprint_layout(h_->ctx, out.data(), n, &n), "footprint_layout");
    out.resize(static_cast<std::size_t>(n));
    return out;
  }

 private:
  rumble_status check(rumble_status s, const char* what) const {
    if (s == RUMBLE_ERROR || s == RUMBLE_FATAL)
      throw Stop(s, std::string("host ") + what + " stopped the run");
    return s;
  }
  const rumble_cosim_host* h_;
  mutable std::vector<rumble_group_residual> residuals_;
};

/// Coupling scheme: the master algorithm over macro steps.
class Coupler : public Component {
 public:
  static constexpr rumble_kind kKind = RUMBLE_KIND_COUPLER;
  virtual void run(const CosimHost& host, double t0, double t_end, double H) = 0;
};

}  // namespace rumble

#endif  // RUMBLE_PLUGIN_COUPLER_HPP
