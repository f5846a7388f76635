#include "distributed/rank_plan.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "memory_model.hpp"

namespace rumble::fem {

namespace {

/// The memory per rank of `p` (its nodes, ranks and largest rank's nodes set).
void plan_memory(RankPlan& p, const PlanChoices& choices) {
  const double share = memory::kHeldBytesPerDof * 3.0 * p.largest_nodes;
  if (p.ranks == 1) {
    p.root_bytes = memory::run_peak_bytes(3.0 * p.nodes);
    return;
  }
  // On many ranks the statics run on the ranks (GAMG, the geometric or the aggregation multigrid)
  // above the factor limit, or at any size when named: each rank its part's; below it rank 0
  // factors the whole (small) operator and frees it.
  const double whole = 3.0 * p.nodes;
  const bool on_ranks = choices.named || whole > memory::kFactorLimitDofs;
  const double per_nonzero = choices.geometric     ? memory::kGeometricRankBytesPerNonzero
                             : choices.aggregation ? memory::kAggregationRankBytesPerNonzero
                                                   : memory::kGamgBytesPerNonzero;
  const double share_statics =
      on_ranks ? per_nonzero * memory::kNonzerosPerDof * 3.0 * p.largest_nodes : 0.0;
  // The implicit steps' factor, each rank its share, once the statics are done.
  const double share_steps = choices.implicit ? memory::rank_factor_bytes(whole, p.ranks) : 0.0;
  p.rank_bytes = memory::kProcessBytes + share + std::max(share_statics, share_steps);
  // Rank 0: its share and the whole mesh (not the operator; with mesh.refine on the ranks the
  // coarse mesh), or the factor's whole operator (below the limit with mesh.refine rank 0
  // refines the whole mesh for the factor: the operator's bytes per DOF count it).
  const double root_statics =
      on_ranks ? share_statics : memory::kHeldBytesPerDof * whole + memory::factor_bytes(whole);
  const double meshed = whole / std::pow(8.0, choices.refine);  // (rank 0's mesh: the coarse one)
  p.root_bytes = memory::kProcessBytes + share + memory::kMeshBytesPerDof * meshed +
                 std::max(root_statics, share_steps);
  // Before that, its meshing and the split: the larger without mesh.refine above the factor
  // limit with the aggregation multigrid (540 B per DOF of the whole against 800 / N + 40).
  p.root_bytes = std::max(p.root_bytes, memory::root_split_bytes(meshed, p.ranks));
}

}  // namespace

RankPlan plan_ranks(double nodes, int ranks, const PlanChoices& choices) {
  RankPlan p;
  p.ranks = std::max(1, ranks);
  p.nodes = nodes;
  if (p.ranks > 1) {
    const double levels = (std::cbrt(p.ranks) - 1.0) / (std::cbrt(2.0) - 1.0);  // g(N)
    p.ghosts = std::min(nodes, kHaloSurface * std::pow(nodes, 2.0 / 3.0) * levels);
  }
  p.largest_nodes = (nodes + p.ghosts) / p.ranks;
  p.halo_bytes = kHaloBytesPerGhost * p.ghosts;
  p.refine = choices.refine;
  plan_memory(p, choices);
  return p;
}

RankPlan plan_split(double nodes, int ranks, double ghosts, double largest_nodes,
                    const PlanChoices& choices) {
  RankPlan p;
  p.ranks = std::max(1, ranks);
  p.nodes = nodes;
  p.ghosts = ghosts;
  p.largest_nodes = largest_nodes;
  p.halo_bytes = kHaloBytesPerGhost * ghosts;
  p.refine = choices.refine;
  plan_memory(p, choices);
  return p;
}

std::string describe(const RankPlan& p, const std::string& source) {
  std::ostringstream m;
  m.precision(3);
  m << "fem: on " << p.ranks << " ranks, from " << source << " (" << p.nodes
    << " nodes): the largest rank about " << p.largest_nodes << " nodes (" << 3.0 * p.largest_nodes
    << " DOFs, ghosts included); a halo of about " << p.ghosts << " ghost nodes, "
    << p.halo_bytes / 1024.0 << " KiB exchanged per step (" << kHaloBytesPerGhost
    << " B per ghost; a surface-to-volume estimate, not a split); memory at the peak about "
    << p.root_bytes / 1e9 << " GB on rank 0 (it meshes, splits and holds the "
    << (p.refine > 0 ? "coarse mesh, each rank refining its part" : "whole mesh") << ") and "
    << p.rank_bytes / 1e9
    << " GB on each other rank (estimates: docs/fem-soil.md, \"Planning the ranks\")";
  return m.str();
}

void check_node_memory(const RankPlan& p, const std::vector<NodeShare>& nodes, double f_max) {
  for (const NodeShare& node : nodes) {
    const double need =
        node.root ? p.root_bytes + (node.ranks - 1) * p.rank_bytes : node.ranks * p.rank_bytes;
    if (need <= node.available) continue;
    std::ostringstream m;
    m.precision(3);
    m << "fem: params/mesh: on " << p.ranks << " ranks a mesh of about " << p.nodes
      << " nodes (mesh.f_max " << f_max << " Hz) needs about " << p.root_bytes / 1e9
      << " GB at its peak on rank 0 and " << p.rank_bytes / 1e9
      << " GB on each other rank (estimates: docs/fem-soil.md, \"Planning the ranks\"): "
      << need / 1e9 << " GB for the " << node.ranks << " rank(s) on "
      << (node.root ? "rank 0's" : "one") << " machine, more than the " << node.available / 1e9
      << " GB it has available (MemAvailable, or the cgroup's limit); start fewer ranks on each "
         "machine (mpirun --map-by), lower mesh.f_max or mesh.radius, or raise mesh.h_near";
    throw std::invalid_argument(m.str());
  }
}

}  // namespace rumble::fem
