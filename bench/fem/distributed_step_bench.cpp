// The FEM soil's explicit step split over the ranks of mpirun (plugins/soils/fem/distributed;
// docs/fem-soil.md, "On many ranks"), against one process's on the same mesh: a Kuhn box of n^3
// cubes of 0.5 m (the medium soil, as fem_bench's BM_ExplicitStep), its K read in single or
// double precision. On one rank the CSR back end (ExplicitSolver's fused product); on N > 1 the
// mesh split by DMPlex and each rank stepping its part, the shared nodes' products summed over
// the ranks by PETSc's star forest each step (two exchanges of 24 B per ghost).
// Prints the best of `repeats` timings of `steps` steps (each timed between barriers, so the
// slowest rank's), the DOF-updates per second of the whole mesh, and the halo; then the largest
// rank's memory (the operator's bytes(), K's compressed rows in it, which a run frees after the
// statics) and the bytes of K its step reads each step (on N > 1 its upper blocks; K's whole
// rows in the step's precision, a value per nonzero and an index per block, beside them).
// usage: mpirun -n N distributed_step_bench [n=46] [steps=100] [single|double] [repeats=5]
#include <mpi.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "distributed/distributed_operator.hpp"
#include "distributed/mesh_partition.hpp"
#include "distributed/part_stiffness.hpp"
#include "mesh/kuhn_box.hpp"
#include "operator/elasticity.hpp"
#include "operator/symmetric_blocks.hpp"
#include "statics/petsc_session.hpp"
#include "time/explicit_solver.hpp"

namespace {

using namespace rumble::fem;

// A step well inside the stable one (the step's cost does not depend on it): the Kuhn mesh's
// stable step is 0.671 h / c_p (docs/numerics.md §4.1).
constexpr double kH = 0.5;

double time_steps(MPI_Comm comm, const ExplicitSolver& solver, ExplicitState& state,
                  const Eigen::VectorXd& f, double dt, int steps) {
  MPI_Barrier(comm);
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) solver.step(state, f, dt);
  MPI_Barrier(comm);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The bytes of K the step reads: the ranks' upper blocks, or one process's (CsrOperator's blocks,
// built again here: the same layout on one part).
std::size_t stepped_bytes(const SoilOperator& op, int ranks, bool single) {
  if (ranks > 1) return static_cast<const DistributedOperator&>(op).stepped_bytes();
  return single ? SymmetricBlocks<float>(op.stiffness(), 1).bytes()
                : SymmetricBlocks<double>(op.stiffness(), 1).bytes();
}

}  // namespace

int main(int argc, char** argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided);
  const int n = argc > 1 ? std::atoi(argv[1]) : 46;
  const int steps = argc > 2 ? std::atoi(argv[2]) : 100;
  const bool single = argc <= 3 || std::string(argv[3]) != "double";
  const int repeats = argc > 4 ? std::atoi(argv[4]) : 5;
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  {
    const auto session = PetscSession::get();
    const FemSettings settings = read_settings(R"({"E": 155e6, "nu": 0.3, "rho": 1800})");
    const double c_p = 1.87 * settings.half_space.shear_wave_speed();  // (nu 0.3: c_p / c_s)
    const double dt = 0.5 * 0.671 * kH / c_p;
    const StepPrecision precision = single ? StepPrecision::kSingle : StepPrecision::kDouble;
    const TetMesh whole = rank == 0 ? kuhn_box(n, kH) : TetMesh{};
    std::optional<MeshPartition> part;
    std::optional<ExplicitSolver> solver;
    long long ghosts = 0;
    if (ranks == 1) {
      solver.emplace(assemble_stiffness(whole, settings), lumped_mass(whole, settings),
                     std::vector<BoundaryNode>{}, false, std::vector<char>(whole.node_count(), 0),
                     0.0, 0.0, static_cast<unsigned>(omp_get_max_threads()), precision);
    } else {
      part.emplace(partition_mesh(MPI_COMM_WORLD, rank == 0 ? &whole : nullptr));
      CsrMatrix K = assemble_stiffness(part->mesh, settings);
      complete_shared_entries(*part, K, MPI_COMM_WORLD);
      Eigen::VectorXd mass = lumped_mass(part->mesh, settings);
      complete_mass(*part, mass);
      for (std::int32_t i = 0; i < part->nodes(); ++i) ghosts += part->owns(i, rank) ? 0 : 1;
      solver.emplace(
          std::make_unique<DistributedOperator>(
              std::move(K), ElementStiffness(part->mesh, settings), std::move(mass),
              std::vector<BoundaryNode>{}, false, std::vector<char>(part->nodes(), 0),
              static_cast<unsigned>(omp_get_max_threads()), precision, *part, MPI_COMM_WORLD),
          0.0, 0.0, 1.0, 0);
    }
    ExplicitState state = solver->rest_state();
    for (Eigen::Index k = 0; k < state.w.size(); ++k) state.w[k] = 1e-6 * ((k * 7919) % 13);
    const Eigen::VectorXd f = Eigen::VectorXd::Zero(state.w.size());
    double best = 1e300;
    for (int r = 0; r < repeats; ++r)
      best = std::min(best, time_steps(MPI_COMM_WORLD, *solver, state, f, dt, steps));
    long long all_ghosts = 0;
    MPI_Reduce(&ghosts, &all_ghosts, 1, MPI_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
    const SoilOperator& op = solver->soil();
    const auto nonzeros = static_cast<double>(op.stiffness().nonzeros());
    const long long mine[4] = {
        static_cast<long long>(op.bytes()), static_cast<long long>(op.stiffness().bytes()),
        static_cast<long long>(stepped_bytes(op, ranks, single)),
        static_cast<long long>(nonzeros * (single ? 4.0 : 8.0) + nonzeros / 9.0 * 4.0)};
    long long most[4] = {0, 0, 0, 0};
    MPI_Reduce(mine, most, 4, MPI_LONG_LONG, MPI_MAX, 0, MPI_COMM_WORLD);
    if (rank == 0) {
      const double dofs = 3.0 * static_cast<double>(whole.node_count());
      std::printf(
          "distributed_step_bench: n %d (%.3g DOFs), %s, %d rank(s) x %d thread(s): %.3g ms "
          "per step, %.3g million DOF-updates per second; halo %lld ghosts, %.3g KiB per step\n",
          n, dofs, single ? "single" : "double", ranks, omp_get_max_threads(), 1e3 * best / steps,
          dofs * steps / best / 1e6, all_ghosts, static_cast<double>(all_ghosts) * 48.0 / 1024.0);
      constexpr double kMiB = 1048576.0;
      std::printf(
          "distributed_step_bench: the largest rank's operator %.1f MiB (K's rows %.1f MiB in "
          "it); its step reads %.1f MiB of K per step (K's whole rows in the step's precision: "
          "%.1f MiB)\n",
          most[0] / kMiB, most[1] / kMiB, most[2] / kMiB, most[3] / kMiB);
    }
  }
  MPI_Finalize();
  return 0;
}
