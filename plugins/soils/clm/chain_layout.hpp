// The layouts the CLM accepts: its neighbour terms couple footprint i to i - 1 and i + 1 at one
// spacing, so the footprints must be equally spaced along one line, in order.
#pragma once

#include <cmath>
#include <rumble/plugin.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace rumble::soils {

/// What is wrong with a chain of two or more footprints at `spacing` [m] ("" when nothing).
inline std::string chain_problem(const std::vector<Footprint>& fp, double spacing, bool same_size) {
  std::ostringstream m;
  if (!(spacing > 0.0) || !std::isfinite(spacing)) {
    m << "footprints must be in order of increasing x along the track; footprint 1 is at x = "
      << fp[1].x << " m, footprint 0 at x = " << fp[0].x << " m";
    return m.str();
  }
  for (std::size_t i = 1; i < fp.size(); ++i) {
    const double expected = fp[0].x + static_cast<double>(i) * spacing;
    if (!(std::abs(fp[i].x - expected) <= 1e-6 * spacing)) {
      m << "footprints must be equally spaced along the track; footprint " << i
        << " is at x = " << fp[i].x << " m, expected " << expected << " m (spacing " << spacing
        << " m)";
    } else if (fp[i].y != fp[0].y) {
      m << "footprints must lie on one line along the track; footprint " << i
        << " is at y = " << fp[i].y << " m, footprint 0 at y = " << fp[0].y << " m";
    } else if (same_size && (fp[i].length != fp[0].length || fp[i].width != fp[0].width)) {
      m << "footprints must all have the size of footprint 0 (" << fp[0].length << " m x "
        << fp[0].width << " m) to be calibrated from soil properties; footprint " << i << " is "
        << fp[i].length << " m x " << fp[i].width << " m";
    } else {
      continue;
    }
    return m.str();
  }
  return "";
}

/// Spacing [m] of the chain (0 for a lone footprint). same_size: the footprints must also be
/// equal (their size enters the calibration). Throws std::invalid_argument naming the first
/// offending footprint, its value, what was expected and what to do.
inline double chain_spacing(const std::vector<Footprint>& fp, bool same_size) {
  if (fp.size() < 2) return 0.0;
  const double spacing = fp[1].x - fp[0].x;
  const std::string problem = chain_problem(fp, spacing, same_size);
  if (problem.empty()) return spacing;
  throw std::invalid_argument("clm: " + problem +
                              "; the chain couples each footprint to its neighbours at one "
                              "spacing (use winkler for other layouts)");
}

}  // namespace rumble::soils
