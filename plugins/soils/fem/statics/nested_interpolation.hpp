// The interpolation from a mesh to its uniform refinement (mesh.refine,
// mesh/uniform_refinement.hpp) for the statics' geometric multigrid (geometric_static_solver.hpp;
// docs/fem-soil.md §7.1): the refined mesh's linear elements span the coarse mesh's and more, so a
// coarse displacement field is a fine one, node for node, through the coarse tetrahedron around
// each fine node: its value there is the coarse nodes' values weighted by the fine node's
// barycentric coordinates. After k refinements those lie on the lattice of step 2^-k
// (mesh/numbered_refinement.hpp): a fine node at a coarse node copies it, one at an edge's midpoint
// averages its ends. The weights are rounded to that lattice, so they are exact (dyadic) and a
// linear field is interpolated to the last bit the coordinates allow.
#pragma once

#include "mesh/tet_mesh.hpp"
#include "operator/row_sparse.hpp"

namespace rumble::fem {

/// fine = refine_uniformly(coarse, levels) up to a renumbering of its nodes (its tetrahedra in
/// refine_uniformly's order: coarse tetrahedron e's children are 8^levels e to 8^levels (e + 1)
/// - 1). One row per fine node, one column per coarse node (nodes, not DOFs: each of the 3
/// displacement components interpolates alike), each row's weights summing to 1. Throws
/// std::invalid_argument when fine is not so refined from coarse (the tetrahedra's counts
/// differ, or a fine node lies off the lattice of its coarse tetrahedron), naming what.
RowSparse nested_interpolation(const TetMesh& coarse, const TetMesh& fine, int levels);

}  // namespace rumble::fem
