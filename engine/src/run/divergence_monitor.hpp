// Watches each soil's footprint displacements for a coupled solution that is blowing up, and does
// what the scenario says (/coupling/divergence): stop the run with the time and the fix, or warn
// once and go on. A displacement beyond `displacement_factor` times the participant's largest
// static footprint displacement counts as diverging: a passing train amplifies the static
// settlement by a few times at most (at the critical speed), an unstable coupling without bound.
// The onset reported is the first time any footprint passed twice its static settlement. Beyond
// 1 m, or a value that is not finite, the run stops whatever the policy (nothing useful follows).
#pragma once

#include <cstddef>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scenario/run_spec.hpp"

namespace rumble {

class DivergenceMonitor {
 public:
  explicit DivergenceMonitor(scenario::DivergenceSpec policy) : policy_(policy) {}

  /// A participant's static footprint displacements [m] (before its first step); returns its
  /// index for check().
  std::size_t watch(const std::string& name, const double* u, std::size_t n);
  /// Its footprint displacements u [m] and velocities v [m/s] (n each) at the end of a final
  /// step ending at t [s]. Throws RunError to stop the run.
  void check(std::size_t participant, const double* u, const double* v, std::size_t n, double t);

  bool detected() const { return t_detected_ < kNever; }
  /// summary.json's "divergence": the policy, and when it was detected and began (null: never).
  nlohmann::json summary() const;

 private:
  static constexpr double kNever = std::numeric_limits<double>::infinity();
  struct Watched {
    std::string name;
    double settlement = 0.0;  // m, largest static |u|
  };
  scenario::DivergenceSpec policy_;
  std::vector<Watched> watched_;
  double t_onset_ = kNever, t_detected_ = kNever;  // s
};

}  // namespace rumble
