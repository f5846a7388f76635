// Renumbering a mesh's nodes along a Morton (Z-order) curve, so that nodes near in space are near
// in memory. The explicit step's K x gathers x at each row's neighbours; with gmsh's own
// numbering those are scattered, and the step ran 1.5x slower per nonzero than on a structured
// box (23 against 37 MDOF/s, 2.1e5 against 3.1e5 DOFs, measured 2026-12-02).
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace rumble::fem {

/// Permutes m.nodes and renames the nodes in its tetrahedra and faces (and in `more_faces`, when
/// given: faces of the same mesh kept elsewhere); the mesh is the same.
void order_nodes_spatially(TetMesh& m, std::vector<Triangle>* more_faces = nullptr);

/// The points' order along the Morton curve (new index -> old), order_nodes_spatially's.
std::vector<std::int32_t> spatial_order(const Eigen::Matrix3Xd& points);

/// Each point's key on the Morton curve through the box [min, max] (order_nodes_spatially's
/// keys when the box is the points' own).
std::vector<std::uint64_t> morton_keys(const Eigen::Matrix3Xd& points, const Eigen::Vector3d& min,
                                       const Eigen::Vector3d& max);

/// The order by Morton key in the box [min, max], then by number (new index -> old): one
/// process's order of a refined mesh's nodes (their numbers: mesh/numbered_refinement.hpp), which
/// a rank gives its part's nodes from the whole mesh's box, so that every rank orders any two
/// nodes as one process does (docs/fem-soil.md §8, "mesh.refine on the ranks").
std::vector<std::int32_t> numbered_spatial_order(const Eigen::Matrix3Xd& points,
                                                 const std::vector<std::int64_t>& number,
                                                 const Eigen::Vector3d& min,
                                                 const Eigen::Vector3d& max);

/// Puts node order[k] at k (order: new index -> old, a permutation) and renames the nodes in
/// the tetrahedra and faces (and in `more_faces`, when given).
void renumber_nodes(TetMesh& m, const std::vector<std::int32_t>& order,
                    std::vector<Triangle>* more_faces = nullptr);

}  // namespace rumble::fem
