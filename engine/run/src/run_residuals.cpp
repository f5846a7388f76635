#include "run/run_residuals.hpp"

#include <algorithm>

namespace rumble {

void RunResiduals::add(const rumble_group_residual& g) {
  const std::string_view name = g.group != nullptr ? g.group : "";
  auto it = groups_.find(name);  // heterogeneous: no string built once the key exists
  if (it == groups_.end()) it = groups_.emplace(std::string(name), Group{}).first;
  Group& group = it->second;
  group.max_absolute = std::max(group.max_absolute, g.absolute);
  group.max_relative = std::max(group.max_relative, g.relative);
  // relative = absolute / scale; a group whose values are all zero so far reports relative =
  // absolute (GroupResiduals' fallback), which tells nothing of the scale.
  if (g.absolute > 0.0 && g.relative > 0.0 && g.relative != g.absolute)
    group.scale = std::max(group.scale, g.absolute / g.relative);
}

double RunResiduals::relative_of(const Group& g) {
  return g.scale > 0.0 ? g.max_absolute / g.scale : g.max_relative;
}

std::map<std::string, double, std::less<>> RunResiduals::relative() const {
  std::map<std::string, double, std::less<>> out;
  for (const auto& [name, g] : groups_) out.emplace(name, relative_of(g));
  return out;
}

std::map<std::string, double, std::less<>> RunResiduals::absolute() const {
  std::map<std::string, double, std::less<>> out;
  for (const auto& [name, g] : groups_) out.emplace(name, g.max_absolute);
  return out;
}

double RunResiduals::largest_relative() const {
  double m = 0.0;
  for (const auto& [name, g] : groups_) m = std::max(m, relative_of(g));
  return m;
}

}  // namespace rumble
