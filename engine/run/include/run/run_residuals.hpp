// The interface residual of a whole run, per channel group, relative to the group's scale over
// the whole run. A coupler reports each step's residual relative to the group's largest |value|
// so far (SDK coupling::GroupResiduals, the only scale known online); a group that starts at
// rest (the footprint velocity) then reads 1 at its first moving step, whatever the coupling
// does, and the largest of those per-step values said nothing (every run of the paper study
// read 1). Here the largest absolute residual is divided by the group's scale at the run's end:
// the largest |value| of the group over the run, which the reports carry as absolute / relative.
#pragma once

#include <rumble/abi.h>

#include <map>
#include <string>

namespace rumble {

class RunResiduals {
 public:
  /// One group's residual of one final step.
  void add(const rumble_group_residual& g);

  /// Group -> largest absolute residual / the group's largest |value| over the run (-).
  std::map<std::string, double, std::less<>> relative() const;
  /// Group -> largest absolute residual, in the group's unit (m, m/s, N).
  std::map<std::string, double, std::less<>> absolute() const;
  /// The largest of relative() (0 without reports).
  double largest_relative() const;

 private:
  struct Group {
    double max_absolute = 0.0;  // the group's unit
    double scale = 0.0;         // largest |value| seen, from absolute / relative
    double max_relative = 0.0;  // the per-step value, kept for a group whose scale never showed
  };
  static double relative_of(const Group& g);
  std::map<std::string, Group, std::less<>> groups_;
};

}  // namespace rumble
