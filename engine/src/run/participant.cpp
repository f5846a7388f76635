#include "run/participant.hpp"

#include <algorithm>

#include "core/errors.hpp"
#include "plugin/instance.hpp"
#include "track/track_participant.hpp"

namespace rumble {

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
std::size_t TrackSide::state_size() const {
  return track_.state_size();
}
void TrackSide::save_state(double* b) const {
  track_.save_state(b);
}
void TrackSide::restore_state(const double* b) {
  track_.restore_state(b);
}

SoilSide::SoilSide(SoilInstance& soil, std::size_t n_footprints)
    : soil_(soil), n_(n_footprints), coeff_(3 * n_footprints, 0.0) {
  input_ = rumble_waveform{0, n_, coeff_.data()};
}
std::string SoilSide::name() const {
  return "soil/" + soil_.type_name();
}
void SoilSide::get_output(double* y) const {
  soil_.motion(y, y + n_, n_);
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
void SoilSide::advance(double t, double H) {
  soil_.advance(t, H, input_);
}
std::size_t SoilSide::state_size() const {
  return soil_.state_size();
}
void SoilSide::save_state(double* b) const {
  soil_.save_state(state_);
  std::copy(state_.begin(), state_.end(), b);
}
void SoilSide::restore_state(const double* b) {
  if (state_.empty()) state_.resize(soil_.state_size());
  std::copy(b, b + state_.size(), state_.begin());
  soil_.restore_state(state_);
}

}  // namespace rumble
