// The participants of a co-simulation as the host sees them: a name ("track", "soil", or an
// extra participant's scenario name), named channel groups on each side, the outputs, the input
// waveform, advance, and checkpoints. The host forwards coupler calls here and times each one.
#pragma once

#include <rumble/abi.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace rumble {

class SoilInstance;
class TrackParticipant;

class Participant {
 public:
  explicit Participant(std::string name) : name_(std::move(name)) {}
  virtual ~Participant() = default;
  /// The name couplers use: "track", "soil", or an extra participant's scenario name.
  const std::string& name() const { return name_; }
  /// What it is, for logs and timings: "vehicle/track", "soil/clm".
  virtual std::string description() const = 0;
  /// description(), kept: a string that a crash record can point at (run/crash_record.hpp).
  const std::string& label() const {
    if (label_.empty()) label_ = description();
    return label_;
  }
  virtual std::size_t output_size() const = 0;
  virtual void get_output(double* y) const = 0;
  virtual void set_input(const rumble_waveform& u) = 0;
  virtual void advance(double t, double H) = 0;
  /// Channel groups of the outputs and of the input waveform (names and units: abi.h).
  const std::vector<rumble_channel_group>& output_groups() const { return outputs_; }
  const std::vector<rumble_channel_group>& input_groups() const { return inputs_; }

  /// Checkpoints, slot < RUMBLE_CHECKPOINT_SLOTS. By default the state is copied into a buffer
  /// held here (allocated once per slot: the track's); a soil goes through its instance's one
  /// checkpoint path instead (SoilInstance::checkpoint_save).
  virtual bool can_checkpoint() const { return state_size() > 0; }
  /// Whether its advance may refuse a step: some plugin in it does not declare
  /// RUMBLE_CAP_NEVER_REFUSES (docs/decisions/0017-never-refuses.md).
  virtual bool may_refuse() const { return true; }
  virtual void checkpoint(std::uint32_t slot);
  virtual void rollback(std::uint32_t slot);
  virtual void free_checkpoint(std::uint32_t slot);

  double wall_seconds = 0.0;  // accumulated time spent in advance()

 private:
  mutable std::string label_;  // description(), made at the first label()

 protected:
  /// The state the default checkpoints copy (0: none); a participant that overrides them needs
  /// none of the three.
  virtual std::size_t state_size() const { return 0; }
  virtual void save_state(std::vector<double>& /*buffer*/) const {}
  virtual void restore_state(const std::vector<double>& /*buffer*/) {}
  void set_groups(std::vector<rumble_channel_group> outputs,
                  std::vector<rumble_channel_group> inputs) {
    outputs_ = std::move(outputs);
    inputs_ = std::move(inputs);
  }
  static void check_slot(std::uint32_t slot);

 private:
  std::string name_;
  std::vector<rumble_channel_group> outputs_, inputs_;
  std::array<std::vector<double>, RUMBLE_CHECKPOINT_SLOTS> slots_;
  std::array<bool, RUMBLE_CHECKPOINT_SLOTS> saved_{};
};

/// The vehicle/track: output footprint_force (n), input footprint_displacement then
/// footprint_velocity (2n).
class TrackSide final : public Participant {
 public:
  explicit TrackSide(TrackParticipant& track);
  std::string description() const override { return "vehicle/track"; }
  std::size_t output_size() const override;
  void get_output(double* y) const override;
  void set_input(const rumble_waveform& u) override;
  void advance(double t, double H) override;
  bool may_refuse() const override;

 private:
  std::size_t state_size() const override;
  void save_state(std::vector<double>& buffer) const override;
  void restore_state(const std::vector<double>& buffer) override;
  TrackParticipant& track_;
};

/// A soil: output footprint_displacement then footprint_velocity (2n), input footprint_force
/// (n). Its input starts as the static footprint forces it was initialized under, held, until a
/// coupler sets another (docs/couplers.md, "The coupler contract"). A soil integrated in the
/// vehicle/track (`integrated_in`: a monolithic coupler, decision 0008) is stepped by the track:
/// its outputs are the track's footprint motion, advancing it is an error, and its state is
/// checkpointed with the track's.
class SoilSide final : public Participant {
 public:
  /// static_force: the n footprint forces [N] the soil's statics were solved under.
  SoilSide(std::string name, SoilInstance& soil, const std::vector<double>& static_force,
           const TrackParticipant* integrated_in = nullptr);
  std::string description() const override;
  std::size_t output_size() const override { return 2 * n_; }
  void get_output(double* y) const override;
  void set_input(const rumble_waveform& u) override;
  void advance(double t, double H) override;
  bool can_checkpoint() const override;
  bool may_refuse() const override;
  void checkpoint(std::uint32_t slot) override;
  void rollback(std::uint32_t slot) override;
  void free_checkpoint(std::uint32_t slot) override;
  SoilInstance& soil() const { return soil_; }
  /// Footprint displacements u [m] and velocities v [m/s] now (n values each).
  void motion(double* u, double* v) const;
  /// The motion to report in the results: that of motion(), except that after a step taken
  /// under a force held constant over it (waveform order 0, the explicit schemes' default) the
  /// velocity is the mean over that step, (u - u at its start) / H. Under a held force a soil
  /// relaxes towards it within the step, so its end-of-step velocity is not its motion's (a
  /// massless soil comes to rest: docs/couplers.md, "The footprint velocity").
  void reported_motion(double* u, double* v) const;
  /// Whether reported_motion() gives the mean velocity over the last step.
  bool reports_step_mean() const { return held_step_ > 0.0; }
  /// The footprint forces [N] the soil took at the end of its last step (the input waveform of
  /// its last advance at tau = 1), n values: what a coupler gave it, which need not be the
  /// track's forces; before its first step the static forces; integrated in the track, the
  /// track's forces now.
  void applied_force(double* f) const;

 private:
  SoilInstance& soil_;
  std::size_t n_;
  const TrackParticipant* integrated_in_;
  std::vector<double> coeff_;  // the force waveform until the next advance
  rumble_waveform input_{0, 0, nullptr};
  std::vector<double> applied_;            // N: the last advance's waveform at tau = 1
  std::vector<double> u_start_, v_start_;  // m, m/s: the motion when the last step began
  double held_step_ = 0.0;                 // s: the last step's H when its force was held; else 0
};

}  // namespace rumble
