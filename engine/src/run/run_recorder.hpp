// Records the run after every macro step into CSV time histories in the results directory:
//   contact.csv           wheel/rail contact force of every wheel [N]
//   vehicles.csv          vehicle DOFs [m or rad]
//   footprint_force.csv   force on the soil at every footprint [N] (down +)
//   footprint_displacement.csv, footprint_velocity.csv   footprint u [m], v [m/s] (down +)
//   interface.csv         coupler's relative interface residual (the largest of its channel
//                         groups'), power [W] and energy [J] exchanged at the cut, and the
//                         coupler's iterations in the macro step (1 for explicit schemes)
//   receivers.csv         vertical velocity of surface receivers [m/s] (soils that offer them)
// and keeps the peaks (PPV) for the summary.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include "run/csv_file.hpp"

namespace rumble {

class ResultsDirectory;
class TrackParticipant;
class SoilInstance;

class RunRecorder {
 public:
  RunRecorder(ResultsDirectory& results, const TrackParticipant& track, const SoilInstance& soil,
              const std::vector<double>& receiver_distances, bool receivers_offered);
  /// Record the state at time t, dt after the previous record (0 for the initial state);
  /// residual: the coupler's relative interface residual of the last macro step, iterations:
  /// its iterations in that step (0 for the initial state).
  void record(double t, double dt, double residual, std::uint32_t iterations);

  const std::vector<double>& peak_footprint_velocity() const { return peak_fp_v_; }
  const std::vector<double>& peak_receiver_velocity() const { return peak_rx_v_; }
  double max_residual() const { return max_residual_; }
  double energy_exchanged() const { return energy_; }
  std::vector<std::string> files() const;

 private:
  const TrackParticipant& track_;
  const SoilInstance& soil_;
  std::unique_ptr<CsvFile> contact_, vehicles_, fp_force_, fp_u_, fp_v_, interface_, receivers_;
  std::vector<double> force_, u_, v_, wheels_, rx_v_, peak_fp_v_, peak_rx_v_;
  double power_ = 0.0, energy_ = 0.0, max_residual_ = 0.0;
  bool first_ = true;
};

}  // namespace rumble
