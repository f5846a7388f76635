// The static state by the geometric multigrid on the ranks (statics.solver geometric under
// mpirun; plugins/soils/fem/distributed/geometric_rank_statics.hpp; issue #33) against one
// process on the same mesh: a Kuhn box of 1 m cubes split over the ranks, each rank's part
// refined after the split (refined_partition.hpp), a load from each node's number, and
//   - the ranks' solution gathered on rank 0 leaves a residual within CG's tolerance (1e-12 of
//     the load) in one process's operator (K + S in double on the whole refined box: an
//     operator the ranks' code never saw) and agrees with one process's CHOLMOD factor;
//   - CG's iterations on the ranks at one process's tolerance (1e-10) are within 1.3 times (plus
//     2) of one process's geometric multigrid (statics/geometric_static_solver.hpp) on the same
//     box: the same levels, the coarse GAMG split over the ranks;
//   - the geometric multigrid on the ranks frees the part's rows in double before its set-up and
//     solves without them (its fine level's product formed from the part's tetrahedra,
//     element_stiffness.hpp): the rows are still freed after the solve;
//   - GAMG on the same parts (statics.solver gamg under mpirun, distributed_statics.hpp) frees
//     the part's rows in double once PETSc's matrix holds them (the soil's memory on the ranks,
//     docs/fem-soil.md §8), builds them again the same to the bit when asked, and its solution
//     agrees with one process's factor as the geometric multigrid's does;
// on the viscous-spring boundary (springs at every boundary node), refined once and twice, and
// on a fixed boundary (held DOFs: identity rows, no interpolation to or from them).
// usage: mpirun -n N fem_geometric_statics_check   (exit code 0: all held; 1: a check failed)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "boundary/absorbing_boundary.hpp"
#include "distributed/distributed_statics.hpp"
#include "distributed/geometric_rank_statics.hpp"
#include "distributed/mesh_partition.hpp"
#include "distributed/part_operator.hpp"
#include "distributed/part_stiffness.hpp"
#include "distributed/refined_partition.hpp"
#include "fem_settings.hpp"
#include "mesh/kuhn_box.hpp"
#include "mesh/node_order.hpp"
#include "mesh/numbered_refinement.hpp"
#include "operator/csr_operator.hpp"
#include "operator/elasticity.hpp"
#include "statics/coarse_level.hpp"
#include "statics/geometric_static_solver.hpp"
#include "statics/petsc_session.hpp"
#include "statics/static_solver.hpp"

namespace {

using namespace rumble::fem;

int rank_of(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}

// A load from each node's number in the whole mesh (the same on every rank) [N].
double load_at(std::int32_t global, int c) {
  return 1e3 * (std::sin(0.37 * global + 1.3 * c) + 0.1 * c);
}

// The whole coarse mesh refined `levels` times on one process, its nodes in the numbering the
// ranks give them (numbered_refinement.hpp).
TetMesh refined_whole(const TetMesh& coarse, int levels) {
  NumberedRefinement fine = refine_numbered(coarse, name_entities(coarse), levels);
  std::vector<std::int32_t> order(fine.number.size());  // new index (the number) -> old
  for (std::size_t i = 0; i < order.size(); ++i)
    order[fine.number[i]] = static_cast<std::int32_t>(i);
  renumber_nodes(fine.mesh, order);
  return fine.mesh;
}

struct RanksSolution {
  Eigen::VectorXd u;       // rank 0: the whole mesh's, in the ranks' numbering
  Eigen::VectorXd u_gamg;  // the same by GAMG on the ranks
  int iterations = 0, loose_iterations = 0, levels = 0;
  bool geometric_freed_rows = false;                         // on every rank, after the solve
  bool gamg_freed_rows = false, rows_rebuilt_alike = false;  // on every rank
};

// True on every rank when `mine` holds on each.
bool on_all(MPI_Comm comm, bool mine) {
  int here = mine ? 1 : 0, all = 0;
  MPI_Allreduce(&here, &all, 1, MPI_INT, MPI_MIN, comm);
  return all == 1;
}

// The part's rows made free to release: built again as the soil builds them
// (distributed_soil.cpp) when next asked for.
void set_rows_source(MPI_Comm comm, const MeshPartition& fine, DistributedOperator& op,
                     const FemSettings& settings) {
  op.set_stiffness_source([&fine, &settings, comm] {  // (op outlives this call)
    CsrMatrix K = assemble_stiffness(fine.mesh, settings);
    complete_shared_entries(fine, K, comm);
    return K;
  });
}

// GAMG's statics on the ranks' parts, into s: whether the rows were freed, then built again
// alike, and the solution gathered on rank 0.
void solve_by_gamg(MPI_Comm comm, const MeshPartition& fine, DistributedOperator& op,
                   const Eigen::VectorXd& f, RanksSolution& s) {
  const std::vector<double> rows = op.stiffness().value();
  DistributedStatics gamg(fine, op, comm);
  s.gamg_freed_rows = on_all(comm, !op.holds_stiffness());
  const Eigen::VectorXd u = gamg.solve(f);
  s.rows_rebuilt_alike = on_all(comm, op.stiffness().value() == rows);  // (collective)
  s.u_gamg = Eigen::VectorXd::Zero(rank_of(comm) == 0 ? 3 * fine.global_nodes : 0);
  fine.from_root->copy_to_roots(u.data(), rank_of(comm) == 0 ? s.u_gamg.data() : nullptr, 3);
}

// The box split, refined `levels` times on the ranks, solved there at 1e-12 and at 1e-10.
RanksSolution solve_on_ranks(MPI_Comm comm, const TetMesh& coarse_box, int levels,
                             const FemSettings& settings,
                             const std::vector<rumble::Footprint>& footprints) {
  const bool root = rank_of(comm) == 0;
  const MeshPartition coarse = partition_mesh(comm, root ? &coarse_box : nullptr, true);
  const MeshPartition fine = refine_partition(comm, coarse, levels);
  const auto op = part_operator(fine, settings, footprints, 2, StepPrecision::kSingle, comm);
  const auto coarse_op =
      part_operator(coarse, settings, footprints, 1, StepPrecision::kDouble, comm);
  Eigen::VectorXd f(3 * fine.nodes());
  for (std::int32_t i = 0; i < fine.nodes(); ++i)
    for (int c = 0; c < 3; ++c) f[3 * i + c] = load_at(fine.global[i], c);
  RanksSolution s;
  set_rows_source(comm, fine, *op, settings);
  GeometricRankStatics tight(fine, *op, coarse, *coarse_op, levels, comm);
  const Eigen::VectorXd u = tight.solve(f);
  s.geometric_freed_rows = on_all(comm, !op->holds_stiffness());
  s.iterations = tight.last_iterations();
  s.levels = tight.levels();
  GeometricRankStatics loose(fine, *op, coarse, *coarse_op, levels, comm, 1e-10);
  loose.solve(f);
  s.loose_iterations = loose.last_iterations();
  s.u = Eigen::VectorXd::Zero(root ? 3 * fine.global_nodes : 0);
  fine.from_root->copy_to_roots(u.data(), root ? s.u.data() : nullptr, 3);
  solve_by_gamg(comm, fine, *op, f, s);
  return s;
}

// One process on the whole refined box against the ranks' solution; true when all held.
bool check_on_one_process(const TetMesh& coarse_box, int levels, const FemSettings& settings,
                          const std::vector<rumble::Footprint>& footprints,
                          const RanksSolution& ranks, const char* name) {
  const TetMesh whole = refined_whole(coarse_box, levels);
  std::vector<BoundaryNode> boundary = absorbing_boundary(whole, settings, footprints);
  std::vector<char> held = held_nodes(whole.node_count(), boundary, settings);
  const CsrOperator op(assemble_stiffness(whole, settings), lumped_mass(whole, settings),
                       std::move(boundary), settings.boundary.springs(), std::move(held), 1,
                       StepPrecision::kDouble);
  Eigen::VectorXd f(whole.dof_count());
  for (std::int32_t g = 0; g < whole.node_count(); ++g)
    for (int c = 0; c < 3; ++c) f[3 * g + c] = op.fixed()[g] ? 0.0 : load_at(g, c);
  Eigen::VectorXd Ku;
  op.stiffness_times(ranks.u, Ku, true);
  for (std::int32_t g = 0; g < whole.node_count(); ++g)
    if (op.fixed()[g]) Ku.segment<3>(3 * g) = ranks.u.segment<3>(3 * g);  // (identity rows)
  const double residual = (f - Ku).norm() / f.norm();
  StaticSolver factor(op, whole.nodes, whole.dof_count());
  const Eigen::VectorXd exact = factor.solve(f);
  const double error = (ranks.u - exact).cwiseAbs().maxCoeff() / exact.cwiseAbs().maxCoeff();
  GeometricStaticSolver one(op, [&] {
    return coarse_level(coarse_box, whole, levels, settings, footprints, op.fixed());
  });
  one.solve(f);
  const double gamg_error =
      (ranks.u_gamg - exact).cwiseAbs().maxCoeff() / exact.cwiseAbs().maxCoeff();
  const bool ok = residual <= 1.05 * GeometricRankStatics::kTolerance && error < 1e-8 &&
                  ranks.loose_iterations <= 1.3 * one.last_iterations() + 2 && gamg_error < 1e-8 &&
                  ranks.geometric_freed_rows && ranks.gamg_freed_rows && ranks.rows_rebuilt_alike;
  std::printf(
      "fem_geometric_statics_check (%s, refined %d times, %lld DOFs): %d levels; on the ranks "
      "(the part's rows %s) %d CG iterations to 1e-12, residual %.3g of the load in one process's "
      "operator, within "
      "%.3g of its factor; to 1e-10 %d iterations, one process's geometric multigrid %d; GAMG on "
      "the ranks within %.3g of the factor, the part's rows %s, %s: %s\n",
      name, levels, static_cast<long long>(whole.dof_count()), ranks.levels,
      ranks.geometric_freed_rows ? "freed" : "NOT FREED", ranks.iterations, residual, error,
      ranks.loose_iterations, one.last_iterations(), gamg_error,
      ranks.gamg_freed_rows ? "freed" : "NOT FREED",
      ranks.rows_rebuilt_alike ? "built again alike" : "NOT BUILT AGAIN ALIKE",
      ok ? "ok" : "FAILED");
  return ok;
}

int check(MPI_Comm comm, int levels, const std::string& boundary, const char* name) {
  const FemSettings settings = read_settings(
      R"({"E": 155e6, "nu": 0.3, "rho": 1800, "boundary": {"type": ")" + boundary + R"("}})");
  const std::vector<rumble::Footprint> footprints = {{2.5, 2.5, 2.0, 1.0}, {4.0, 2.5, 2.0, 1.0}};
  const TetMesh coarse_box = kuhn_box(6, 5, 4, 1.0);
  const RanksSolution ranks = solve_on_ranks(comm, coarse_box, levels, settings, footprints);
  int failed = 0;
  if (rank_of(comm) == 0)
    failed = check_on_one_process(coarse_box, levels, settings, footprints, ranks, name) ? 0 : 1;
  MPI_Bcast(&failed, 1, MPI_INT, 0, comm);
  return failed;
}

}  // namespace

int main(int argc, char** argv) {
  int provided = 0;  // (MPI as the engine starts it; PETSc neither starts nor finalises it)
  MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided);
  int failed = 0;
  {
    const auto session = rumble::fem::PetscSession::get();
    failed += check(MPI_COMM_WORLD, 1, "viscous_spring", "viscous-spring boundary");
    failed += check(MPI_COMM_WORLD, 2, "viscous_spring", "viscous-spring boundary");
    failed += check(MPI_COMM_WORLD, 1, "fixed", "fixed boundary");
  }
  MPI_Finalize();  // (the session's PETSc is left to the process's end: petsc_session.hpp)
  return failed == 0 ? 0 : 1;
}
