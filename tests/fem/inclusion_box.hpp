// A Kuhn box with a stiff inclusion, shared by the explicit step's tests: a corner of 2 x 2 x 2
// cubes (layer 0) 6 times stiffer than the rest (layer 1), so that its nodes alone set the
// single-rate step (c_p 2.45 times faster there), as a few short elements do on the railway
// meshes; local time stepping then has fine nodes to take.
#pragma once

#include <Eigen/Core>

#include "fem_settings.hpp"
#include "mesh/kuhn_box.hpp"
#include "settings_from_params.hpp"

namespace rumble::fem::test {

inline constexpr double kInclusionBoxEdge = 0.5;  // m, the cubes' edge

/// 6 x 6 x 6 cubes of kInclusionBoxEdge; the inclusion is the corner at the origin.
inline TetMesh box_with_inclusion() {
  TetMesh m = kuhn_box(6, kInclusionBoxEdge);
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const std::int32_t node : m.tets[e]) centre += m.node(node) / 4.0;
    m.layer[e] = (centre.array() < 2.0 * kInclusionBoxEdge).all() ? 0 : 1;
  }
  return m;
}

/// The medium soil (docs/physics.md §1.4) with the inclusion as its layer 0.
inline FemSettings inclusion_soil() {
  FemSettings s = rumble::test::soil_settings(155e6, 0.3, 1800.0);
  s.layers = {{1.0, soils::SoilProperties{930e6, 0.3, 1800.0}}};
  return s;
}

}  // namespace rumble::fem::test
