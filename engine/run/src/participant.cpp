#include "run/participant.hpp"

#include <algorithm>

#include "core/errors.hpp"
#include "plugin/instance.hpp"
#include "track/track_participant.hpp"

namespace rumble {
namespace {

// Group names and units at the cut (abi.h, rumble_channel_group).
constexpr const char* kForce = "footprint_force";
constexpr const char* kDisplacement = "footprint_displacement";
constexpr const char* kVelocity = "footprint_velocity";

std::vector<rumble_channel_group> force_group(std::size_t n) {
  return {{kForce, "N", 0, n}};
}
std::vector<rumble_channel_group> motion_groups(std::size_t n) {
  return {{kDisplacement, "m", 0, n}, {kVelocity, "m/s", n, n}};
}

}  // namespace

void Participant::check_slot(std::uint32_t slot) {
  if (slot >= RUMBLE_CHECKPOINT_SLOTS) {
    throw RunError("checkpoint slot " + std::to_string(slot) + " does not exist (slots 0.." +
                   std::to_string(RUMBLE_CHECKPOINT_SLOTS - 1) + ")");
  }
}

void Participant::checkpoint(std::uint32_t slot) {
  check_slot(slot);
  save_state(slots_[slot]);
  saved_[slot] = true;
}

void Participant::rollback(std::uint32_t slot) {
  check_slot(slot);
  if (!saved_[slot])
    throw RunError("restore from checkpoint slot " + std::to_string(slot) + " never saved");
  restore_state(slots_[slot]);
}

void Participant::free_checkpoint(std::uint32_t slot) {
  check_slot(slot);
  std::vector<double>().swap(slots_[slot]);
  saved_[slot] = false;
}

// ---------------------------------------------------------------- track

TrackSide::TrackSide(TrackParticipant& track) : Participant("track"), track_(track) {
  const std::size_t n = track.interface_size();
  set_groups(force_group(n), motion_groups(n));
}
std::size_t TrackSide::output_size() const {
  return track_.interface_size();
}
void TrackSide::get_output(double* y) const {
  track_.footprint_forces(y);
}
void TrackSide::set_input(const rumble_waveform& u) {
  track_.set_input(u);
}
void TrackSide::advance(double t, double H) {
  track_.advance(t, H);
}
bool TrackSide::may_refuse() const {
  // The track's own equations take any step; its vehicles' plugins may refuse one.
  for (const VehicleSet::Vehicle& v : track_.vehicles().vehicles())
    if (v.instance->may_refuse()) return true;
  return false;
}
std::size_t TrackSide::state_size() const {
  return track_.state_size();
}
void TrackSide::save_state(std::vector<double>& b) const {
  b.resize(track_.state_size());
  track_.save_state(b.data());
}
void TrackSide::restore_state(const std::vector<double>& b) {
  track_.restore_state(b.data());
}

// ---------------------------------------------------------------- soil

SoilSide::SoilSide(std::string name, SoilInstance& soil, const std::vector<double>& static_force,
                   const TrackParticipant* integrated_in)
    : Participant(std::move(name)),
      soil_(soil),
      n_(static_force.size()),
      integrated_in_(integrated_in),
      coeff_(3 * n_, 0.0),
      applied_(static_force),
      u_start_(n_, 0.0),
      v_start_(n_, 0.0) {
  // Held at its static forces until a coupler says otherwise: a soil advanced without an input
  // stays loaded as its statics were solved, as the track holds its static footprint motion.
  std::copy(static_force.begin(), static_force.end(), coeff_.begin());
  input_ = rumble_waveform{0, n_, coeff_.data()};
  set_groups(motion_groups(n_), force_group(n_));
}
std::string SoilSide::description() const {
  return "soil/" + soil_.type_name();
}
void SoilSide::get_output(double* y) const {
  motion(y, y + n_);
}
void SoilSide::motion(double* u, double* v) const {
  if (integrated_in_ == nullptr) return soil_.motion(u, v, n_);
  for (std::size_t i = 0; i < n_; ++i) {
    u[i] = integrated_in_->footprint_u(i);
    v[i] = integrated_in_->footprint_v(i);
  }
}
void SoilSide::set_input(const rumble_waveform& u) {
  if (u.n != n_ || u.order > 2) {
    throw RunError("soil input: expected " + std::to_string(n_) +
                   " force channels of order <= 2, got " + std::to_string(u.n) + " of order " +
                   std::to_string(u.order));
  }
  std::copy(u.coeff, u.coeff + (u.order + 1) * n_, coeff_.begin());
  input_.order = u.order;
}
void SoilSide::reported_motion(double* u, double* v) const {
  motion(u, v);
  if (!reports_step_mean()) return;
  for (std::size_t i = 0; i < n_; ++i) v[i] = (u[i] - u_start_[i]) / held_step_;
}
void SoilSide::applied_force(double* f) const {
  if (integrated_in_ != nullptr) return integrated_in_->footprint_forces(f);
  std::copy(applied_.begin(), applied_.end(), f);
}
void SoilSide::advance(double t, double H) {
  if (integrated_in_ != nullptr) {
    throw RunError("soil '" + soil_.type_name() +
                   "' is integrated in the vehicle/track (a monolithic coupler): advance the "
                   "track only");
  }
  const bool held = input_.order == 0;
  if (held) motion(u_start_.data(), v_start_.data());
  soil_.advance(t, H, input_);
  held_step_ = held ? H : 0.0;
  // What it took at the step's end, summed in the order of the coefficients (c0 + c1 + c2), as a
  // coupler that interpolates to the track's new forces wrote them.
  for (std::size_t i = 0; i < n_; ++i) {
    double sum = 0.0;
    for (std::uint32_t k = 0; k <= input_.order; ++k) sum += coeff_[k * n_ + i];
    applied_[i] = sum;
  }
}
bool SoilSide::may_refuse() const {
  if (integrated_in_ != nullptr) return false;  // advancing it is an error, never a refusal
  return soil_.may_refuse();
}
bool SoilSide::can_checkpoint() const {
  if (integrated_in_ != nullptr) return false;  // its state is the track's
  return soil_.can_checkpoint();
}
void SoilSide::checkpoint(std::uint32_t slot) {
  check_slot(slot);
  soil_.checkpoint_save(slot);
}
void SoilSide::rollback(std::uint32_t slot) {
  check_slot(slot);
  soil_.checkpoint_restore(slot);
}
void SoilSide::free_checkpoint(std::uint32_t slot) {
  check_slot(slot);
  soil_.checkpoint_free(slot);
}

}  // namespace rumble
