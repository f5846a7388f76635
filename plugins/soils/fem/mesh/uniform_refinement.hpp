// Uniform refinement of a tetrahedral mesh (issue #33, docs/fem-soil.md §2 "mesh.refine"): each
// tetrahedron into eight by its edge midpoints (four corner tetrahedra, similar to the parent,
// and the inner octahedron cut along its shortest diagonal, which keeps the quality bounded
// under repeated refinement), each ground and truncation triangle into four, layers and surface
// tags kept. Straight-sided: the new nodes lie on the coarse mesh's edges, so the domain and its
// surfaces are the coarse mesh's (exact for the box and the flat ground; a hemisphere's curved
// truncation surface stays faceted at the coarse size).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace rumble::fem {

/// The mesh with every tetrahedron cut into eight. Node numbering: the coarse nodes keep their
/// numbers, the midpoints follow in the order their edges are first met over the tetrahedra
/// (deterministic); tetrahedron e's children are 8 e to 8 e + 7, a surface triangle f's 4 f to
/// 4 f + 3. Each child depends on its parent's nodes alone, so a part of a mesh (some of its
/// tetrahedra and their faces, numbered locally) refines into the children the whole mesh's
/// refinement has: `midpoint_ends` (when given) receives each new node's edge (its two coarse
/// nodes), from which a caller that knows the whole mesh's edges names the node as the whole
/// refinement does (docs/fem-soil.md §8, "Not yet": the parts refined on the ranks). Throws
/// std::invalid_argument when a surface triangle is no face of a tetrahedron (its edge has no
/// midpoint), naming it.
TetMesh refine_uniformly(const TetMesh& coarse,
                         std::vector<std::array<std::int32_t, 2>>* midpoint_ends = nullptr);

/// `levels` refinements in turn (0: the mesh as given): 8^levels times the tetrahedra.
TetMesh refine_uniformly(const TetMesh& coarse, int levels);

}  // namespace rumble::fem
