// Smoothed aggregation's first step below the mesh (amg_preconditioner.hpp) without the whole
// products in memory. The plain way forms P = (I - W A) P0, R = P^T and A P whole, then R (A P):
// at 1e6 DOFs (27e6, 27e6 and 75e6 nonzeros of 12 B) 1.5 GB beside A, and the statics' peak
// was 4.6 GB (docs/fem-soil.md section 7.2). Here the coarse rows are made a chunk of aggregates
// at a time: the rows of P and A P that chunk needs (its nodes and two rings of neighbours) are
// formed, used and dropped, and P is kept only as the V-cycle keeps it, in float (and without its
// transpose: transposed_product.hpp). Every entry is
// summed in the same order as sparse_product (sparse_product.hpp) sums it on the whole matrices,
// so the hierarchy is the same to the bit (tests/fem/static_solver_test.cpp); the rows near a
// chunk's border are formed again for the next chunk (docs/fem-soil.md section 7.2 has the
// set-up's time against the whole products').
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "operator/sparse_product.hpp"
#include "statics/mesh_matrix.hpp"

namespace rumble::fem {

/// Nodes per chunk of aggregates: its rows of P (two rings of neighbours, about twice its nodes)
/// and of A P (one ring, 1.4 times) take some 25 MB at about 90 nonzeros per row of A P, twice
/// that while they are formed, however large the mesh; chunks of 16384 nodes took 0.13 GB more
/// at the statics' peak on a box of 2.1e5 DOFs (the rows near a chunk's border are formed for
/// each chunk that reaches them: the smaller the chunk, the more often).
inline constexpr std::int64_t kMeshChunkNodes = 1 << 12;

/// The mesh's nodes in aggregates: each node's aggregate, and each aggregate's first coarse DOF
/// (then the coarse DOFs' count): aggregate a owns coarse DOFs [start[a], start[a + 1]).
struct MeshAggregates {
  std::vector<std::int32_t> of_node;
  std::vector<Eigen::Index> coarse_start;
};

/// P = P0 - W (A P0) (w: W's diagonal; P0: the tentative prolongator, its entries on the
/// aggregates' DOFs) into P in float, and P^T A P into coarse. A and P0 are taken
/// (P0 left empty) and freed before the coarse matrix is put together. threads >= 1;
/// chunk_nodes: the mesh's nodes per chunk of aggregates (at least; a test makes it small).
void coarsen_mesh_matrix(MeshMatrix A, RowSparse& P0, const Eigen::VectorXd& w,
                         const MeshAggregates& aggregates, unsigned threads, RowSparse& coarse,
                         RowSparseFloat& P, std::int64_t chunk_nodes = kMeshChunkNodes);

}  // namespace rumble::fem
