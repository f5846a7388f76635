// Soil field snapshots (ABI 1.1 write_fields) at the cadence of /outputs/fields: the soil writes
// each fields/soil_<k>.vtu itself; the engine names the files and keeps the ParaView index
// soil.pvd (time of each snapshot) valid after every one, so a run that stops early still opens.
// No write goes through a symbolic link: fields/ is a real directory, whatever stands at a
// snapshot's name is removed before the soil writes it, and soil.pvd is a new file each time.
// Each name is listed in the results directory's manifest before it is written.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace rumble {

class ResultsDirectory;
class SoilInstance;

class FieldWriter {
 public:
  /// interval [s] > 0 between snapshots, the first at t = 0.
  FieldWriter(ResultsDirectory& results, SoilInstance& soil, double interval);
  /// Writes a snapshot when t [s] has reached the next one's time.
  void at(double t);
  std::size_t snapshots() const { return times_.size(); }
  std::string index_file() const { return "soil.pvd"; }

 private:
  void write_index();
  ResultsDirectory& results_;
  SoilInstance& soil_;
  double interval_;
  std::vector<double> times_;
  std::vector<std::string> files_;  // relative to dir_
};

}  // namespace rumble
