// The coarse level of the statics' geometric multigrid (geometric_static_solver.hpp;
// docs/fem-soil.md §7.1): with mesh.refine the soil's mesh is gmsh's coarse mesh refined uniformly,
// and that coarse mesh, kept, gives the multigrid its coarse problem directly: K + S assembled
// again on it (the same elasticity and the same boundary springs, at the coarse size), and the
// interpolation of the nested linear elements (nested_interpolation.hpp). No Galerkin product of
// the fine matrix is formed, and the fine matrix is never needed assembled.
#pragma once

#include <Eigen/Core>
#include <rumble/plugin.hpp>
#include <vector>

#include "fem_settings.hpp"
#include "mesh/tet_mesh.hpp"
#include "operator/row_sparse.hpp"

namespace rumble::fem {

struct CoarseLevel {
  /// K + S of the coarse mesh in double, 3 DOFs per node, held DOFs as identity rows and columns
  /// (effective_matrix.hpp's full_combination).
  RowSparse matrix;
  /// The coarse mesh's node coordinates [m] (the coarse solve's rigid-body modes).
  Eigen::Matrix3Xd nodes;
  /// Fine nodes x coarse nodes, the nested linear elements' weights (one weight for the node's
  /// 3 DOFs); rows of held fine nodes and columns of held coarse nodes zero (a held DOF neither
  /// takes nor gives a correction).
  RowSparse interpolation;
};

/// The coarse level for the soil on `fine` = coarse refined `levels` times (nested_interpolation's
/// order), with the plugin's settings and footprints (the boundary's springs are fitted to them)
/// and fine_held: per fine node, held (the fine operator's fixed nodes).
CoarseLevel coarse_level(const TetMesh& coarse, const TetMesh& fine, int levels,
                         const FemSettings& settings, const std::vector<Footprint>& footprints,
                         const std::vector<char>& fine_held);

}  // namespace rumble::fem
