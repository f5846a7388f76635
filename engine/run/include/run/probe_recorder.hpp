// Receivers of an ABI 1.1 soil (probes): named points, possibly at depth, whose three velocity
// and displacement components the soil samples inside its steps. The engine takes the samples
// after every final macro step and writes them to receivers.csv, one row per sample:
//   t [s], then per probe: vx vy vz [m/s], ux uy uz [m]   (z down +, abi.h)
// and keeps the peaks: vertical PPV max|vz| and three-component PPV max|v|.
#pragma once

#include <rumble/abi.h>

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "plugin/instance.hpp"
#include "results/csv_file.hpp"
#include "scenario/run_spec.hpp"

namespace rumble {

class ResultsDirectory;

class ProbeRecorder {
 public:
  /// t_end [s]: the run's end, for projecting receivers.csv's size from its first samples;
  /// size_confirmed (--yes): beyond the limit is wanted.
  ProbeRecorder(ResultsDirectory& results, SoilInstance& soil,
                const std::vector<scenario::ReceiverSpec>& points, double t_end,
                bool size_confirmed);
  /// Writes the samples the soil recorded since the last call. The first samples after t = 0
  /// give how many the soil takes per second: a receivers.csv projected beyond the limit on CSV
  /// bytes (scenario/run_size.hpp) stops the run there with the projection and the fix, unless
  /// confirmed (the soil samples inside its own steps, which validation cannot count).
  void take();
  /// [{name, x_m, y_m, depth_m, ppv_m_s (vertical), ppv_3c_m_s, resolved_f_hz (null: the
  /// soil does not say)}]
  nlohmann::json peaks() const;
  /// How the soil finds its resolved frequencies ("": it does not say).
  std::string resolution_rule() const { return resolution_ ? resolution_->rule : ""; }
  std::string file() const { return csv_->path().filename().string(); }

 private:
  SoilInstance& soil_;
  std::vector<scenario::ReceiverSpec> points_;
  std::unique_ptr<CsvFile> csv_;
  std::vector<double> times_, values_;
  double t_end_;         // s
  bool size_confirmed_;  // --yes
  double samples_ = 0;   // written so far
  bool projected_ = false;

  /// Throws RunError when receivers.csv would outgrow the limit at the rate sampled so far.
  void check_projected_size(double t) const;
  std::vector<double> ppv_z_, ppv_3c_;
  std::optional<SoilInstance::ProbeResolution> resolution_;  // ABI 1.3, when the soil says

  void log_resolution() const;
};

}  // namespace rumble
