// Records the run into CSV time histories in the results directory, each participant when a
// coupler reports its step final (most schemes finish all of them together; two_step finishes
// the track on its reduced soil first, then the soil):
//   track:  contact.csv           wheel/rail contact force of every wheel [N]
//           vehicles.csv          vehicle DOFs [m or rad]
//   soil:   footprint_force.csv   force the soil took at every footprint at the step's end [N]
//                                 (down +): the coupler's input to it, which is the track's
//                                 force for gauss_seidel (track first), two_step and monolithic,
//                                 an extrapolated one for jacobi, an iterate for implicit, a
//                                 prescribed load for a coupler that applies its own
//                                 (SoilSide::applied_force; docs/couplers.md)
//           footprint_displacement.csv, footprint_velocity.csv   footprint u [m], v [m/s] (down +);
//                                 v after a step under a held force is the mean over the step
//                                 (SoilSide::reported_motion)
//           interface.csv         coupler's relative interface residual (the largest of its
//                                 channel groups'), power [W] and energy [J] that the footprint
//                                 forces the soil took did on it, the coupler's iterations in
//                                 the macro step (1 for explicit schemes), the energy the track
//                                 put through the cut (its forces on the footprint motion it
//                                 used) [J], and the energy residual: track's minus soil's [J],
//                                 the energy the coupling created (0 for monolithic). Energies
//                                 are sums of 1/2 (F_k + F_k+1) (u_k+1 - u_k) over the records:
//                                 displacement increments are right at any step, end-of-step
//                                 velocities of an explicit scheme are not (issue #10); the
//                                 macro step that ended [s] (0 at t = 0; varies with an
//                                 adaptive step or a halved refused one), and the relative
//                                 residual of the step's predictor: the coupling error, of
//                                 the scheme's order (StepOutcome::predictor_residual)
//           receivers.csv         vertical velocity of surface receivers [m/s] (soils that offer
//                                 them)
//   extra soils of the coupler (e.g. two_step's reduced_soil):
//           <name>_footprint_displacement.csv, <name>_footprint_velocity.csv
// and keeps the peaks (PPV) for the summary.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include "results/csv_file.hpp"

namespace rumble {

class ResultsDirectory;
class SoilSide;
class TrackParticipant;

class RunRecorder {
 public:
  RunRecorder(ResultsDirectory& results, const TrackParticipant& track, const SoilSide& soil,
              const std::vector<const SoilSide*>& extras,
              const std::vector<double>& receiver_distances, bool receivers_offered);
  /// The track's state at time t [s].
  void record_track(double t);
  /// The relative interface residuals of a macro step [-]: the final one, the predictor's.
  struct StepResiduals {
    double final = 0.0, predictor = 0.0;
  };
  /// The soil's state at time t [s]; residuals: the coupler's relative interface residuals of
  /// the last macro step, iterations: its iterations in that step (0 for the initial state).
  void record_soil(double t, StepResiduals residuals, std::uint32_t iterations, double macro_step);
  /// Extra soil e's footprint motion at time t [s].
  void record_extra(std::size_t e, double t);
  /// Everything at t = 0 (the static state).
  void record_initial();
  /// Room for this many records of each participant (no allocation while recording).
  void reserve(std::size_t records);

  const std::vector<double>& peak_footprint_velocity() const { return peak_fp_v_; }
  const std::vector<double>& peak_receiver_velocity() const { return peak_rx_v_; }
  double energy_exchanged() const { return energy_; }
  /// [J]: the energy the track put through the cut; the last recorded energy residual.
  double track_energy() const { return track_energy_.empty() ? 0.0 : track_energy_.back(); }
  double energy_residual() const { return energy_residual_; }
  std::vector<std::string> files() const;

 private:
  /// Work [J] of footprint forces F on footprint displacements u sampled at the records.
  class CutWork {
   public:
    void resize(std::size_t n);
    /// Adds the work since the last sample (none at the first); returns the total.
    double add(const double* force, const double* u);

   private:
    std::vector<double> force_, u_;
    double total_ = 0.0;
    bool first_ = true;
  };
  struct ExtraFiles {
    const SoilSide* side;
    std::unique_ptr<CsvFile> u, v;
  };
  const TrackParticipant& track_;
  const SoilSide& soil_;
  std::unique_ptr<CsvFile> contact_, vehicles_, fp_force_, fp_u_, fp_v_, interface_, receivers_;
  std::vector<ExtraFiles> extras_;
  std::vector<double> force_, u_, v_, wheels_, rx_v_, peak_fp_v_, peak_rx_v_;
  double energy_ = 0.0;  // J
  CutWork soil_work_, track_work_;
  // The track's energy [J] at each of its records (the soil's k-th record compares with the
  // track's k-th: the same time), from its forces [N] on the footprint motion [m] it used.
  std::vector<double> track_energy_, track_force_, track_u_;
  std::size_t soil_records_ = 0;
  double energy_residual_ = 0.0;  // J
};

}  // namespace rumble
