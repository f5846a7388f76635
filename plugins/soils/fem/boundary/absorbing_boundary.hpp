// The truncation surface's per-node impedance: Lysmer-Kuhlemeyer dashpots rho c_p along the
// normal and rho c_s along the tangents [N s/m^3], and a symmetric 3 x 3 spring [N/m^3] that
// gives the static support (docs/fem-soil.md section 3): by default fitted so that the
// half-space's static field of the footprints' load holds exactly (section 3.2), or Liu et
// al.'s (2006) alpha_N G / r along the normal and alpha_T G / r along the tangents (r the
// distance from the footprints). Each times the node's share of the surface (a third of every
// adjacent triangle); the normal is the area-weighted mean of the adjacent faces'. Lumped on
// the node: no extra unknowns, the explicit step stays explicit.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <rumble/plugin.hpp>
#include <vector>

#include "fem_settings.hpp"
#include "mesh/tet_mesh.hpp"
#include "mesh/track_region.hpp"
#include "operator/boundary_blocks.hpp"

namespace rumble::fem {

/// Every node of the truncation surface, with its blocks for the settings' boundary kind (for a
/// fixed boundary only node and area are meaningful). The half-space springs are fitted to a
/// uniform pressure on the footprints; distances are measured from their rectangle.
std::vector<BoundaryNode> absorbing_boundary(const TetMesh& mesh, const FemSettings& settings,
                                             const std::vector<Footprint>& footprints);
/// The same with one load spread over the region's rectangle (a point when it has no area).
std::vector<BoundaryNode> absorbing_boundary(const TetMesh& mesh, const FemSettings& settings,
                                             const TrackRegion& region);

/// Per node of a mesh of `nodes` nodes, whether it is held (never moves): the truncation
/// surface's nodes under boundary.type fixed, and behind a matched layer, where the viscous-spring
/// blocks or dashpots made the discrete layer grow at every step tried (docs/fem-soil.md section
/// 3.1); none under the other kinds.
std::vector<char> held_nodes(Eigen::Index nodes, const std::vector<BoundaryNode>& boundary,
                             const FemSettings& settings);

// The two halves of absorbing_boundary, for a mesh split over ranks (distributed/part_pieces.hpp):
// a node's share of the surface sums the faces around it, which may lie on several ranks.
/// The truncation surface's nodes of `mesh`, each with its share of the faces' area [m^2] and
/// their area-weighted outward normal [m^2] (not yet a unit vector): sums over its faces.
struct SurfaceShares {
  std::vector<std::int32_t> nodes;
  std::vector<double> area;
  std::vector<Eigen::Vector3d> weighted_normal;
};
SurfaceShares truncation_shares(const TetMesh& mesh, const TrackRegion& region);
/// The boundary nodes with their blocks from the complete shares of the surface.
std::vector<BoundaryNode> fitted_boundary(const TetMesh& mesh, const FemSettings& settings,
                                          const std::vector<Footprint>& footprints,
                                          const SurfaceShares& shares);

}  // namespace rumble::fem
