// `rumble mesh FILE --ranks N` with the mesh in hand (issue #33; docs/fem-soil.md, "Planning the
// ranks"): the mesh split into N parts on this one process by the partitioner a run on N ranks
// uses (mesh_partition.hpp, partition_on_one_process), nothing distributed, and counted as the
// run counts its split (distributed_soil.cpp's "the mesh split over N ranks" line): each part's
// tetrahedra and nodes (every node its tetrahedra touch, owned or ghost), and the ghosts over
// all parts (a node on k parts is a ghost on k - 1 of them, whichever owns it).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "distributed/rank_plan.hpp"
#include "mesh/tet_mesh.hpp"

namespace rumble::fem {

struct MeshSplit {
  std::int64_t nodes = 0;                // the whole mesh's
  std::vector<std::int64_t> tetrahedra;  // per part
  std::vector<std::int64_t> held;        // per part: its nodes, owned and ghost
  std::int64_t ghosts = 0;               // over all parts
  int parts() const { return static_cast<int>(held.size()); }
  std::int64_t largest() const;  // the most nodes a part holds
};

/// `whole` split into `ranks` >= 2 parts on this process (a PETSc session is started for it).
/// Throws std::runtime_error when PETSc fails.
MeshSplit split_mesh(const TetMesh& whole, int ranks);

/// One line for the log: the split's counts per part, the halo (ghosts, bytes per sub-step) and
/// `plan`'s memory per rank (plan_split of this split).
std::string describe(const MeshSplit& split, const RankPlan& plan);

}  // namespace rumble::fem
