// Soil field snapshots (ABI 1.1 write_fields) at the cadence of /outputs/fields: the soil writes
// each fields/soil_<k>.vtu itself (on N ranks soil_<k>.pvtu and its pieces soil_<k>_<r>.vtu, one
// per rank: rumble/abi.h, write_fields); the engine names the files and keeps the ParaView index
// soil.pvd (time of each snapshot) valid after every one, so a run that stops early still opens.
// No write goes through a symbolic link: fields/ is a real directory, whatever stands at a
// snapshot's name is removed before the soil writes it, and soil.pvd is a new file each time.
// Each name is listed in the results directory's manifest before it is written.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace rumble {

/// Largest total of field snapshots a run writes unconfirmed [bytes] (docs/scenario.md, "Run
/// size"): 10 GiB, as for the time histories.
inline constexpr double kMaxFieldBytes = 10.0 * (1u << 30);

class ResultsDirectory;
class SoilInstance;

class FieldWriter {
 public:
  /// interval [s] > 0 between snapshots, the first at t = 0; t_end [s]: the run's end;
  /// size_confirmed (--yes): beyond the limit is wanted.
  FieldWriter(ResultsDirectory& results, SoilInstance& soil, double interval, double t_end,
              bool size_confirmed);
  /// Writes a snapshot when t [s] has reached the next one's time. The first snapshot's size
  /// times the snapshots the run will take is the fields' projected size: beyond
  /// kMaxFieldBytes it stops the run there (RunError, with the projection and the fix) unless
  /// confirmed, since a snapshot's size is the soil's (its mesh), which validation cannot see.
  void at(double t);
  std::size_t snapshots() const { return times_.size(); }
  std::string index_file() const { return "soil.pvd"; }

 private:
  void write_index();
  /// Throws RunError when the snapshots would outgrow kMaxFieldBytes at the first one's size
  /// (its files: the .vtu, or the .pvtu and its pieces).
  void check_projected_size(const std::vector<std::filesystem::path>& first) const;
  ResultsDirectory& results_;
  SoilInstance& soil_;
  double interval_;
  double t_end_;         // s
  bool size_confirmed_;  // --yes
  std::vector<double> times_;
  std::vector<std::string> files_;  // relative to dir_
};

}  // namespace rumble
