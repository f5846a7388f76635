// The two sides of the cut as the co-simulation host sees them: outputs, input waveform,
// advance, checkpoint. The host forwards coupler calls here and times each participant.
#pragma once

#include <rumble/abi.h>

#include <cstddef>
#include <string>
#include <vector>

namespace rumble {

class SoilInstance;
class TrackParticipant;

class Participant {
 public:
  virtual ~Participant() = default;
  virtual std::string name() const = 0;
  virtual std::size_t output_size() const = 0;
  virtual void get_output(double* y) const = 0;
  virtual void set_input(const rumble_waveform& u) = 0;
  virtual void advance(double t, double H) = 0;
  virtual std::size_t state_size() const = 0;
  virtual void save_state(double* buffer) const = 0;
  virtual void restore_state(const double* buffer) = 0;
  double wall_seconds = 0.0;  // accumulated time spent in advance()
};

/// Track side: output F (n), input u then v (2n).
class TrackSide final : public Participant {
 public:
  explicit TrackSide(TrackParticipant& track) : track_(track) {}
  std::string name() const override { return "vehicle/track"; }
  std::size_t output_size() const override;
  void get_output(double* y) const override;
  void set_input(const rumble_waveform& u) override;
  void advance(double t, double H) override;
  std::size_t state_size() const override;
  void save_state(double* buffer) const override;
  void restore_state(const double* buffer) override;

 private:
  TrackParticipant& track_;
};

/// Soil side: output u then v (2n), input F (n).
class SoilSide final : public Participant {
 public:
  SoilSide(SoilInstance& soil, std::size_t n_footprints);
  std::string name() const override;
  std::size_t output_size() const override { return 2 * n_; }
  void get_output(double* y) const override;
  void set_input(const rumble_waveform& u) override;
  void advance(double t, double H) override;
  std::size_t state_size() const override;
  void save_state(double* buffer) const override;
  void restore_state(const double* buffer) override;

 private:
  SoilInstance& soil_;
  std::size_t n_;
  std::vector<double> coeff_;  // the force waveform until the next advance
  rumble_waveform input_{0, 0, nullptr};
  mutable std::vector<double> state_;
};

}  // namespace rumble
