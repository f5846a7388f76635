// Uniform refinement of a tetrahedral mesh (issue #33, docs/fem-soil.md §2 "mesh.refine"): each
// tetrahedron into eight by its edge midpoints (four corner tetrahedra, similar to the parent,
// and the inner octahedron cut along its shortest diagonal, which keeps the quality bounded
// under repeated refinement), each ground and truncation triangle into four, layers and surface
// tags kept. Straight-sided: the new nodes lie on the coarse mesh's edges, so the domain and its
// surfaces are the coarse mesh's (exact for the box and the flat ground; a hemisphere's curved
// truncation surface stays faceted at the coarse size).
#pragma once

#include "mesh/tet_mesh.hpp"

namespace rumble::fem {

/// The mesh with every tetrahedron cut into eight. Node numbering: the coarse nodes keep their
/// numbers, the midpoints follow in the order their edges are first met over the tetrahedra
/// (deterministic). Throws std::invalid_argument when a surface triangle is no face of a
/// tetrahedron (its edge has no midpoint), naming it.
TetMesh refine_uniformly(const TetMesh& coarse);

/// `levels` refinements in turn (0: the mesh as given): 8^levels times the tetrahedra.
TetMesh refine_uniformly(const TetMesh& coarse, int levels);

}  // namespace rumble::fem
