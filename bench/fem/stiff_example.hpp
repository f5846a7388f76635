// The stiff example's soil and sleepers (scenarios/examples/stiff_soil_fem.json: a graded gmsh
// hemisphere of R = 15 m, resolution near_distance 5 m, 30 sleeper footprints), for the benches
// that need a real mesh rather than a structured box.
#pragma once

#include <vector>

#include "fem_settings.hpp"
#include "settings_from_params.hpp"

namespace rumble::bench {

/// The stiff soil (docs/physics.md §1.4) meshed for f_max [Hz].
inline fem::FemSettings stiff_example(double f_max) {
  fem::FemSettings s = test::soil_settings(750e6, 0.3, 1800.0);
  s.mesh.radius = 15.0;
  s.mesh.f_max = f_max;
  s.mesh.near_distance = 5.0;
  return s;
}

/// 30 sleepers at 0.6 m, 2.6 m x 0.26 m, centred on x = 0.
inline std::vector<Footprint> stiff_example_sleepers() {
  std::vector<Footprint> fp;
  for (int i = 0; i < 30; ++i) fp.push_back({(i - 14.5) * 0.6, 0.0, 2.6, 0.26});
  return fp;
}

}  // namespace rumble::bench
