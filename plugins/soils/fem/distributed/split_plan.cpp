#include "distributed/split_plan.hpp"

#include <algorithm>
#include <sstream>
#include <utility>

#include "distributed/mesh_partition.hpp"
#include "statics/petsc_session.hpp"

namespace rumble::fem {

std::int64_t MeshSplit::largest() const {
  return held.empty() ? 0 : *std::max_element(held.begin(), held.end());
}

MeshSplit split_mesh(const TetMesh& whole, int ranks) {
  const auto session = PetscSession::get();
  const std::vector<int> part_of = partition_on_one_process(whole, ranks);
  MeshSplit s;
  s.nodes = whole.node_count();
  s.tetrahedra.assign(static_cast<std::size_t>(ranks), 0);
  s.held.assign(static_cast<std::size_t>(ranks), 0);
  // Per node, the last part that counted it: each part's tetrahedra are visited together.
  std::vector<std::vector<std::size_t>> tets_of(static_cast<std::size_t>(ranks));
  for (std::size_t e = 0; e < part_of.size(); ++e)
    tets_of[static_cast<std::size_t>(part_of[e])].push_back(e);
  std::vector<int> counted(static_cast<std::size_t>(s.nodes), -1);
  for (int p = 0; p < ranks; ++p) {
    for (const std::size_t e : tets_of[static_cast<std::size_t>(p)])
      for (const std::int32_t v : whole.tets[e])
        if (counted[static_cast<std::size_t>(v)] != p) {
          counted[static_cast<std::size_t>(v)] = p;
          ++s.held[static_cast<std::size_t>(p)];
        }
    s.tetrahedra[static_cast<std::size_t>(p)] =
        static_cast<std::int64_t>(tets_of[static_cast<std::size_t>(p)].size());
  }
  for (const std::int64_t h : s.held) s.ghosts += h;
  s.ghosts -= s.nodes;  // (every node held once is owned: the rest are ghosts)
  return s;
}

std::string describe(const MeshSplit& split, const RankPlan& plan) {
  const auto range = [](const std::vector<std::int64_t>& v) {
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    return std::to_string(*lo) + "-" + std::to_string(*hi);
  };
  std::ostringstream m;
  m.precision(3);
  m << "fem: on " << split.parts() << " ranks, from the mesh split on one process (" << split.nodes
    << " nodes; PT-Scotch through PETSc, as a run splits it): tetrahedra per rank "
    << range(split.tetrahedra) << ", nodes " << range(split.held)
    << " (ghosts included; the largest rank " << 3.0 * static_cast<double>(split.largest())
    << " DOFs); a halo of " << split.ghosts << " ghost nodes, " << plan.halo_bytes / 1024.0
    << " KiB exchanged per step (" << kHaloBytesPerGhost
    << " B per ghost); memory at the peak about " << plan.root_bytes / 1e9
    << " GB on rank 0 (it meshes, splits and holds the whole mesh) and " << plan.rank_bytes / 1e9
    << " GB on the largest other rank (estimates from the split: docs/fem-soil.md, \"Planning "
       "the ranks\")";
  return m.str();
}

}  // namespace rumble::fem
