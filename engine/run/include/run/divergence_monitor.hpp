// Watches each soil's footprint displacements for a coupled solution that is blowing up, and does
// what the scenario says (/coupling/divergence): stop the run with the time and the fix, or warn
// once and go on. A displacement beyond `displacement_factor` times the participant's largest
// static footprint displacement counts as diverging: a passing train amplifies the static
// settlement by a few times at most (at the critical speed), an unstable coupling without bound.
// A soil with no static load (static displacements below 1 um: a coupler that prescribes the
// forces) has nothing to scale that bound by: it is not applied there, and the growth, the
// velocity limit and the hard limits watch it (docs/couplers.md, "Divergence").
// The onset reported is the first time any footprint passed twice its static settlement. Beyond
// 1 m, or a value that is not finite, the run stops whatever the policy (nothing useful follows).
// Growth counts before size: a footprint speed that keeps growing at one exponential rate past
// twice anything the run did before (run/growth_watch.hpp) is diverging too, reported with its
// rate per macro step, long before it is large (an unstable coupling grows from its first step;
// a slow one can double every 12 ms for 0.2 s and still be under 0.3 m/s).
#pragma once

#include <cstddef>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "run/growth_watch.hpp"
#include "scenario/run_spec.hpp"

namespace rumble {

class DivergenceMonitor {
 public:
  explicit DivergenceMonitor(scenario::DivergenceSpec policy) : policy_(policy) {}

  /// A participant's static footprint displacements [m] (before its first step); returns its
  /// index for check().
  std::size_t watch(const std::string& name, const double* u, std::size_t n);
  /// Its footprint displacements u [m] and velocities v [m/s] (n each) at the end of a final
  /// step of length H [s] ending at t [s]. Throws RunError to stop the run.
  void check(std::size_t participant, const double* u, const double* v, std::size_t n, double t,
             double H);

  bool detected() const { return t_detected_ < kNever; }
  /// summary.json's "divergence": the policy, the scenario's soil's displacement bound [m] (null
  /// without a static load), and when it was detected and began (null: never).
  nlohmann::json summary() const;

 private:
  static constexpr double kNever = std::numeric_limits<double>::infinity();
  struct Watched {
    std::string name;
    double settlement = 0.0;   // m, largest static |u|
    double bound = kNever;     // m, displacement_factor x settlement; kNever: no static load
    std::vector<double> u;     // m, the footprints at the end of the last step
    std::vector<double> v;     // m/s, their velocity then
    std::vector<double> rate;  // m/s, their mean velocity over it
    GrowthWatch growth;
    std::optional<Growth> growing;  // what the last step's window end saw
  };
  /// Feeds the step's largest footprint speed, |v| or |du| / H (a massless soil under explicit
  /// coupling reports a velocity below what it moves), and the half change of either from the
  /// step before (its part that flips sign every step) to w.growth.
  static void watch_growth(Watched& w, const double* u, const double* v, std::size_t n, double t,
                           double H);
  /// Declares divergence: throws when the run stops, warns once when it goes on.
  void diverged(std::ostringstream& m, bool stop_anyway, double t);
  scenario::DivergenceSpec policy_;
  std::vector<Watched> watched_;
  double t_onset_ = kNever, t_detected_ = kNever;  // s
  std::optional<Growth> growth_;                   // what the growth watch saw, when it fired
};

}  // namespace rumble
