// A part refined on its rank (distributed/refined_partition.hpp; docs/fem-soil.md §8).
#include "distributed/refined_partition.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "distributed/node_matching.hpp"
#include "mesh/node_order.hpp"

namespace rumble::fem {
namespace {

/// The fine part's nodes that other ranks hold too (1) and their owners, from the rendezvous of
/// the nodes on the coarse part's seam.
std::pair<std::vector<char>, std::vector<int>> seam_owners(MPI_Comm comm,
                                                           const NumberedRefinement& fine,
                                                           int rank) {
  std::vector<std::int64_t> number;
  std::vector<std::int32_t> local;
  for (std::size_t v = 0; v < fine.number.size(); ++v)
    if (fine.on_seam[v] != 0) {
      number.push_back(fine.number[v]);
      local.push_back(static_cast<std::int32_t>(v));
    }
  const std::vector<NodeMatch> match = match_nodes(comm, number, local);
  std::vector<char> shared(fine.number.size(), 0);
  std::vector<int> owner(fine.number.size(), rank);
  for (std::size_t k = 0; k < match.size(); ++k)
    if (match[k].holders > 1) {
      shared[local[k]] = 1;
      owner[local[k]] = match[k].owner;
    }
  return {std::move(shared), std::move(owner)};
}

/// The halo's leaves: each ghost among the shared nodes [0, part.shared) and its owner's local
/// number of it, from a second rendezvous (the local numbers are final now).
std::vector<ForestLeaf> refined_halo(MPI_Comm comm, const MeshPartition& part, int rank) {
  std::vector<std::int64_t> number(part.global.begin(), part.global.begin() + part.shared);
  std::vector<std::int32_t> local(static_cast<std::size_t>(part.shared));
  for (std::int32_t k = 0; k < part.shared; ++k) local[k] = k;
  const std::vector<NodeMatch> match = match_nodes(comm, number, local);
  std::vector<ForestLeaf> leaves;
  for (std::int32_t k = 0; k < part.shared; ++k) {
    if (match[k].owner != part.owner[k])  // (the same holders choose the same owner)
      throw std::logic_error("fem: refined node " + std::to_string(part.global[k]) +
                             " changed its owner between the rendezvous");
    if (match[k].owner != rank) leaves.push_back({k, match[k].owner, match[k].owner_local});
  }
  return leaves;
}

/// The one process's numbers of the fine part's tetrahedra and ground faces: per level, a
/// tetrahedron's children are 8 e .. 8 e + 7, a face's 4 f .. 4 f + 3.
void number_children(const MeshPartition& coarse, int levels, MeshPartition& part) {
  const std::int32_t tets = 1 << (3 * levels), faces = 1 << (2 * levels);
  part.tet_global.resize(part.mesh.tets.size());
  for (std::size_t c = 0; c < part.tet_global.size(); ++c)
    part.tet_global[c] = coarse.tet_global[c / tets] * tets + static_cast<std::int32_t>(c % tets);
  part.ground_global.resize(part.mesh.ground.size());
  for (std::size_t g = 0; g < part.ground_global.size(); ++g)
    part.ground_global[g] =
        coarse.ground_global[g / faces] * faces + static_cast<std::int32_t>(g % faces);
}

}  // namespace

MeshPartition refine_partition(MPI_Comm comm, const MeshPartition& coarse, int levels) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (coarse.names.edge.size() != coarse.mesh.tets.size())
    throw std::logic_error("fem: refine_partition needs partition_mesh(..., named = true)");
  const RefinedCounts counts = refined_counts(coarse.names, levels);
  if (counts.nodes > std::numeric_limits<std::int32_t>::max() ||
      counts.tets > std::numeric_limits<std::int32_t>::max())
    throw std::invalid_argument("fem: params/mesh/refine: " + std::to_string(levels) +
                                " refinements make " + std::to_string(counts.nodes) + " nodes, " +
                                std::to_string(counts.tets) +
                                " tetrahedra, beyond 2^31 - 1; lower mesh.refine or mesh.f_max");
  std::vector<char> seam(static_cast<std::size_t>(coarse.nodes()), 0);
  std::fill_n(seam.begin(), coarse.shared, 1);
  NumberedRefinement fine = refine_numbered(coarse.mesh, coarse.names, levels, seam);
  const auto [shared, owner] = seam_owners(comm, fine, rank);
  // One process's order (mesh/node_order.hpp) from the whole mesh's box, which is the coarse
  // mesh's (the new nodes are midpoints); the shared nodes first.
  Eigen::Vector3d min = coarse.mesh.nodes.rowwise().minCoeff(),
                  max = coarse.mesh.nodes.rowwise().maxCoeff();
  MPI_Allreduce(MPI_IN_PLACE, min.data(), 3, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(MPI_IN_PLACE, max.data(), 3, MPI_DOUBLE, MPI_MAX, comm);
  std::vector<std::int32_t> order =  // (new -> old)
      numbered_spatial_order(fine.mesh.nodes, fine.number, min, max);
  // (shared by reference, not captured: Clang 14 cannot capture a structured binding)
  const std::vector<char>& is_shared = shared;
  std::stable_partition(order.begin(), order.end(),
                        [&is_shared](std::int32_t v) { return is_shared[v] != 0; });
  const std::vector<std::uint64_t> keys = morton_keys(fine.mesh.nodes, min, max);
  renumber_nodes(fine.mesh, order);
  MeshPartition part;
  part.mesh = std::move(fine.mesh);
  part.global_nodes = counts.nodes;
  part.global_tetrahedra = counts.tets;
  for (std::size_t k = 0; k < order.size(); ++k) {
    part.global.push_back(static_cast<std::int32_t>(fine.number[order[k]]));
    part.owner.push_back(owner[order[k]]);
    part.morton.push_back(keys[order[k]]);
    if (shared[order[k]] != 0) part.shared = static_cast<std::int32_t>(k + 1);
  }
  part.by_global.resize(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) part.by_global[k] = static_cast<std::int32_t>(k);
  std::sort(part.by_global.begin(), part.by_global.end(),
            [&](std::int32_t a, std::int32_t b) { return part.global[a] < part.global[b]; });
  number_children(coarse, levels, part);
  part.halo = std::make_unique<StarForest>(comm, part.shared, refined_halo(comm, part, rank));
  part.halo->make_exchange_buffers();
  std::vector<ForestLeaf> from_root(order.size());
  for (std::size_t k = 0; k < order.size(); ++k)
    from_root[k] = {static_cast<std::int32_t>(k), 0, part.global[k]};
  part.from_root = std::make_unique<StarForest>(
      comm, rank == 0 ? static_cast<std::int32_t>(counts.nodes) : 0, from_root);
  return part;
}

}  // namespace rumble::fem
