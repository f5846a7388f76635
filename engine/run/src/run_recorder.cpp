#include "run/run_recorder.hpp"

#include <algorithm>
#include <cmath>

#include "plugin/instance.hpp"
#include "results/results_directory.hpp"
#include "run/participant.hpp"
#include "track/track_participant.hpp"

namespace rumble {
namespace {

std::vector<std::string> footprint_columns(const TrackParticipant& track, const char* unit) {
  std::vector<std::string> cols{"t [s]"};
  for (const rumble_footprint& f : track.footprints()) {
    char name[64];
    std::snprintf(name, sizeof name, "x=%.3f m [%s]", f.x, unit);
    cols.emplace_back(name);
  }
  return cols;
}

}  // namespace

RunRecorder::RunRecorder(ResultsDirectory& results, const TrackParticipant& track,
                         const SoilSide& soil, const std::vector<const SoilSide*>& extras,
                         const std::vector<double>& receiver_distances, bool receivers_offered)
    : track_(track), soil_(soil) {
  const std::size_t n = track.interface_size();
  const VehicleSet& vs = track.vehicles();
  std::vector<std::string> cols{"t [s]"};
  for (std::size_t w = 0; w < vs.wheel_count(); ++w) {
    const auto [vi, k] = vs.wheel_owner(w);
    cols.push_back(vs.vehicles()[vi].name + " wheel " + std::to_string(k) + " [N]");
  }
  contact_ = std::make_unique<CsvFile>(results.file("contact.csv"), cols);
  cols = {"t [s]"};
  for (const auto& v : vs.vehicles())
    for (std::size_t j = 0; j < v.instance->dof_count(); ++j)
      cols.push_back(v.name + " q" + std::to_string(j));
  vehicles_ = std::make_unique<CsvFile>(results.file("vehicles.csv"), cols);
  fp_force_ =
      std::make_unique<CsvFile>(results.file("footprint_force.csv"), footprint_columns(track, "N"));
  fp_u_ = std::make_unique<CsvFile>(results.file("footprint_displacement.csv"),
                                    footprint_columns(track, "m"));
  fp_v_ = std::make_unique<CsvFile>(results.file("footprint_velocity.csv"),
                                    footprint_columns(track, "m/s"));
  interface_ = std::make_unique<CsvFile>(
      results.file("interface.csv"),
      std::vector<std::string>{"t [s]", "relative residual [-]", "power at cut [W]",
                               "energy exchanged [J]", "iterations [-]", "track energy at cut [J]",
                               "energy residual [J]", "macro step [s]", "predictor residual [-]"});
  for (const SoilSide* e : extras) {
    extras_.push_back(
        {e,
         std::make_unique<CsvFile>(results.file(e->name() + "_footprint_displacement.csv"),
                                   footprint_columns(track, "m")),
         std::make_unique<CsvFile>(results.file(e->name() + "_footprint_velocity.csv"),
                                   footprint_columns(track, "m/s"))});
  }
  if (receivers_offered && !receiver_distances.empty()) {
    cols = {"t [s]"};
    for (double d : receiver_distances) cols.push_back("d=" + std::to_string(d) + " m [m/s]");
    receivers_ = std::make_unique<CsvFile>(results.file("receivers.csv"), cols);
    rx_v_.assign(receiver_distances.size(), 0.0);
    peak_rx_v_.assign(receiver_distances.size(), 0.0);
  }
  force_.assign(n, 0.0);
  u_.assign(n, 0.0);
  track_force_.assign(n, 0.0);
  track_u_.assign(n, 0.0);
  soil_work_.resize(n);
  track_work_.resize(n);
  v_.assign(n, 0.0);
  peak_fp_v_.assign(n, 0.0);
  wheels_.assign(vs.wheel_count(), 0.0);
}

void RunRecorder::record_initial() {
  record_track(0.0);
  record_soil(0.0, {}, 0, 0.0);
  for (std::size_t e = 0; e < extras_.size(); ++e) record_extra(e, 0.0);
}

void RunRecorder::CutWork::resize(std::size_t n) {
  force_.assign(n, 0.0);
  u_.assign(n, 0.0);
}

double RunRecorder::CutWork::add(const double* force, const double* u) {
  for (std::size_t i = 0; i < force_.size(); ++i) {
    if (!first_) total_ += 0.5 * (force_[i] + force[i]) * (u[i] - u_[i]);
    force_[i] = force[i];
    u_[i] = u[i];
  }
  first_ = false;
  return total_;
}

void RunRecorder::reserve(std::size_t records) {
  track_energy_.reserve(records);
}

void RunRecorder::record_track(double t) {
  for (std::size_t w = 0; w < wheels_.size(); ++w) wheels_[w] = track_.contact_force(w);
  contact_->row(t, wheels_.data(), wheels_.size());
  vehicles_->row(t, track_.vehicle_q().data(), static_cast<std::size_t>(track_.vehicle_q().size()));
  // The track's forces on the footprint motion it used.
  track_.footprint_forces(track_force_.data());
  for (std::size_t i = 0; i < track_force_.size(); ++i) track_u_[i] = track_.footprint_u(i);
  track_energy_.push_back(track_work_.add(track_force_.data(), track_u_.data()));
}

void RunRecorder::record_soil(double t, StepResiduals residuals, std::uint32_t iterations,
                              double macro_step) {
  const std::size_t n = force_.size();
  // The force the soil really took, which the coupler chose: an explicit scheme may give it an
  // extrapolated one, a prescribed-load coupler its own; before its first step, the static ones.
  soil_.applied_force(force_.data());
  fp_force_->row(t, force_.data(), n);
  soil_.reported_motion(u_.data(), v_.data());
  double power = 0.0;  // W: work done on the soil per second, now
  for (std::size_t i = 0; i < n; ++i) {
    power += force_[i] * v_[i];
    peak_fp_v_[i] = std::max(peak_fp_v_[i], std::abs(v_[i]));
  }
  energy_ = soil_work_.add(force_.data(), u_.data());
  fp_u_->row(t, u_.data(), n);
  fp_v_->row(t, v_.data(), n);
  const double track_energy = soil_records_ < track_energy_.size() ? track_energy_[soil_records_]
                              : track_energy_.empty()              ? 0.0
                                                                   : track_energy_.back();
  ++soil_records_;
  energy_residual_ = track_energy - energy_;
  const double iface[8] = {residuals.final, power,
                           energy_,         static_cast<double>(iterations),
                           track_energy,    energy_residual_,
                           macro_step,      residuals.predictor};
  interface_->row(t, iface, 8);
  if (receivers_) {
    soil_.soil().receiver_velocity(rx_v_.data(), rx_v_.size());
    for (std::size_t r = 0; r < rx_v_.size(); ++r)
      peak_rx_v_[r] = std::max(peak_rx_v_[r], std::abs(rx_v_[r]));
    receivers_->row(t, rx_v_.data(), rx_v_.size());
  }
}

void RunRecorder::record_extra(std::size_t e, double t) {
  ExtraFiles& x = extras_[e];
  x.side->reported_motion(u_.data(), v_.data());
  x.u->row(t, u_.data(), u_.size());
  x.v->row(t, v_.data(), v_.size());
}

std::vector<std::string> RunRecorder::files() const {
  std::vector<std::string> out;
  for (const auto* f :
       {&contact_, &vehicles_, &fp_force_, &fp_u_, &fp_v_, &interface_, &receivers_})
    if (*f) out.push_back((*f)->path().filename().string());
  for (const ExtraFiles& x : extras_) {
    out.push_back(x.u->path().filename().string());
    out.push_back(x.v->path().filename().string());
  }
  return out;
}

}  // namespace rumble
