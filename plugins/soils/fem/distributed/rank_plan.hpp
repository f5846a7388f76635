// What a run on N ranks will cost each rank, estimated before it is split (issue #33;
// docs/fem-soil.md, "On many ranks", "Planning the ranks"): for `rumble mesh FILE --ranks N`,
// which meshes on one process, and for the check of each node's memory before a run on the
// ranks meshes; with the mesh in hand `rumble mesh` splits it (split_plan.hpp) and plan_split
// takes the split's counts. Before, the halo is a surface-to-volume estimate: N parts cut a mesh of
// n nodes on surfaces through about kHaloSurface n^(2/3) g(N) nodes in all (recursive bisection:
// the first cut through n^(2/3) nodes, each later level of cuts through 2^(1/3) times the
// previous level's; g(N) = (N^(1/3) - 1) / (2^(1/3) - 1)), each such node a ghost on one rank.
// The memory per rank is the soil's one-process model (memory_model.hpp) applied to what each
// rank holds today: rank 0 the whole mesh, its operator and the statics (as one process) beside
// its share; every other rank its share of nodes, owned and ghost.
#pragma once

#include <string>
#include <vector>

namespace rumble::fem {

/// Ghosts per n^(2/3) of a 2-way cut [-]: PT-Scotch's splits gave 0.79 (2 ranks) and 0.91 (3)
/// on the graded mesh of tests/mpi/fem_small.json, 0.89 and 0.91 on a Kuhn box of 3315 nodes
/// (docs/fem-soil.md, "Planning the ranks"); a plane through a box of k^3 nodes holds k^2.
inline constexpr double kHaloSurface = 0.9;

/// Bytes a ghost costs each explicit sub-step: its row of the product to its owner and back,
/// 3 doubles each way (docs/fem-soil.md, "The step").
inline constexpr double kHaloBytesPerGhost = 48.0;

struct RankPlan {
  int ranks = 1;
  double nodes = 0.0;          // the whole mesh's
  double ghosts = 0.0;         // over all ranks (the halo)
  double largest_nodes = 0.0;  // the largest rank's, owned and ghost
  double halo_bytes = 0.0;     // exchanged per explicit sub-step, all ranks [bytes]
  double root_bytes = 0.0;     // rank 0's peak resident memory [bytes]
  double rank_bytes = 0.0;     // any other rank's [bytes]
  int refine = 0;              // mesh.refine on the ranks: rank 0 holds the coarse mesh only
};

/// What the run's settings choose that a rank's memory depends on.
struct PlanChoices {
  /// The statics solved on the ranks at any size (statics.solver named), else only above the
  /// factor limit, rank 0 factoring below it.
  bool named = false;
  /// The levels each rank refines its part by after the split (mesh.refine), rank 0 holding the
  /// coarse mesh, 8^-refine of the whole's nodes and tetrahedra (a refinement into eight has
  /// about 8 times the nodes).
  int refine = 0;
  /// The ranks' statics by the geometric multigrid (statics.solver geometric, or auto with
  /// mesh.refine), its memory rather than GAMG's.
  bool geometric = false;
  /// The implicit scheme (integrator.scheme implicit): each rank holds its share of the steps'
  /// factor (memory_model.hpp, rank_factor_bytes) once the statics are done.
  bool implicit = false;
  /// Without the geometric multigrid: the aggregation multigrid's memory (statics.solver
  /// aggregation, or auto) rather than GAMG's on PETSc's copy of K (statics.solver gamg).
  bool aggregation = false;
};

/// The plan for a mesh of `nodes` nodes on `ranks` >= 1 ranks with the settings' `choices`.
RankPlan plan_ranks(double nodes, int ranks, const PlanChoices& choices = {});

/// The plan for an actual split (split_plan.hpp): its ghosts over all ranks and the largest
/// rank's nodes, owned and ghost, in place of the estimates; the memory per rank from them.
RankPlan plan_split(double nodes, int ranks, double ghosts, double largest_nodes,
                    const PlanChoices& choices = {});

/// One line for the log: nodes and DOFs on the largest rank, the halo (ghosts, bytes per
/// sub-step), the memory of rank 0 and of each other rank; `source` says where the node count
/// comes from ("the plan's estimate", "the mesh").
std::string describe(const RankPlan& plan, const std::string& source);

/// One machine's ranks: how many of a run's ranks it runs (rank 0 among them or not) and the
/// memory it has available [bytes].
struct NodeShare {
  int ranks = 0;
  bool root = false;
  double available = 0.0;
};

/// Throws std::invalid_argument (naming params/mesh, the estimate, the node and the fixes) when
/// the ranks on some node would together need more memory at their peak than it has available.
/// f_max: mesh.f_max [Hz], quoted in the message.
void check_node_memory(const RankPlan& plan, const std::vector<NodeShare>& nodes, double f_max);

}  // namespace rumble::fem
