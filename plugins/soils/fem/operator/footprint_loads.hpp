// The cut's operators on the mesh: a footprint force F_j [N] is a uniform pressure F_j / A_j on
// the footprint's rectangle, whose consistent nodal forces are F_j w_ij on the vertical DOFs,
// w_ij = (integral of N_i over the rectangle) / A_j, sum_i w_ij = 1; the footprint's reported
// displacement is the area average of the vertical displacement, sum_i w_ij u_zi, with the same
// weights: B and B^T (abi.h rumble_matrix INPUT), so the power F . u is the work the mesh sees.
#pragma once

#include <cstdint>
#include <rumble/plugin.hpp>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace rumble::fem {

struct NodalWeight {
  std::int32_t node = 0;
  double weight = 0.0;  // [-]
};

using FootprintWeights = std::vector<std::vector<NodalWeight>>;  // per footprint

/// Weights of each footprint from the ground faces inside its rectangle (the mesh embeds the
/// rectangles, so faces do not straddle their edges). Throws std::invalid_argument when a
/// footprint's meshed area differs from length x width by more than 1 % (outside the mesh, or a
/// mesh that does not follow the footprints), with both areas.
FootprintWeights footprint_weights(const TetMesh& mesh, const std::vector<Footprint>& footprints);

/// Every node of any footprint, once each, ascending: where the footprints' forces act.
std::vector<std::int32_t> loaded_nodes(const FootprintWeights& weights);

/// The footprint's area-averaged vertical component of x (3 per node): one row of B^T.
inline double footprint_average(const std::vector<NodalWeight>& footprint, const double* x) {
  double s = 0.0;
  for (const NodalWeight& w : footprint) s += w.weight * x[3 * w.node + 2];
  return s;
}

}  // namespace rumble::fem
