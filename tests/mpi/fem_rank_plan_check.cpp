// The FEM soil's checks of a split before and after it is made (plugins/soils/fem/distributed;
// issue #33; docs/fem-soil.md, "Planning the ranks"), under mpirun -n N:
//   - a mesh that leaves a rank without tetrahedra (one tetrahedron over N >= 2 ranks) is
//     refused on every rank with the counts and the fix, not a hang or a crash;
//   - the halo that `rumble mesh --ranks N` estimates (rank_plan.hpp, surface-to-volume) is
//     within a factor kWithin of the ghosts of PT-Scotch's actual split of a Kuhn box.
// usage: mpirun -n N fem_rank_plan_check   (exit code 0: all held; 1: a check failed)
#include <cstdio>
#include <stdexcept>
#include <string>

#include "distributed/mesh_partition.hpp"
#include "distributed/rank_plan.hpp"
#include "mesh/kuhn_box.hpp"
#include "statics/petsc_session.hpp"

namespace {

using rumble::fem::MeshPartition;
using rumble::fem::TetMesh;

/// The estimate against the split: within this factor either way [-].
constexpr double kWithin = 1.3;

int rank_of(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}

int empty_rank_refused(MPI_Comm comm) {
  TetMesh one;  // a single tetrahedron: N >= 2 ranks cannot all have one
  one.nodes.resize(3, 4);
  one.nodes << 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1;
  one.tets.push_back({0, 1, 2, 3});
  one.layer.push_back(0);
  std::string said;
  try {
    rumble::fem::partition_mesh(comm, rank_of(comm) == 0 ? &one : nullptr);
  } catch (const std::runtime_error& e) {
    said = e.what();
  }
  const bool ok = said.find("tetrahedra over") != std::string::npos &&
                  said.find("left a rank without any") != std::string::npos &&
                  said.find("run on fewer ranks") != std::string::npos;
  std::printf(
      "fem_rank_plan_check: rank %d: %s %s\n", rank_of(comm),
      ok ? "refused:" : "FAILED, expected the refusal of an empty rank, got:", said.c_str());
  return ok ? 0 : 1;
}

int halo_as_estimated(MPI_Comm comm) {
  const TetMesh whole = rumble::fem::kuhn_box(16, 14, 12, 0.5);
  const MeshPartition part =
      rumble::fem::partition_mesh(comm, rank_of(comm) == 0 ? &whole : nullptr);
  long long mine = 0, ghosts = 0, nodes = part.global_nodes;
  for (const int owner : part.owner) mine += owner != rank_of(comm) ? 1 : 0;
  MPI_Allreduce(&mine, &ghosts, 1, MPI_LONG_LONG, MPI_SUM, comm);
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const double estimate = rumble::fem::plan_ranks(static_cast<double>(nodes), ranks).ghosts;
  const double ratio = estimate / static_cast<double>(ghosts);
  const bool ok = ratio <= kWithin && ratio >= 1.0 / kWithin;
  if (rank_of(comm) == 0)
    std::printf(
        "fem_rank_plan_check: a Kuhn box of %lld nodes on %d ranks: %lld ghosts split, "
        "%.0f estimated (ratio %.3f)%s\n",
        nodes, ranks, ghosts, estimate, ratio, ok ? "" : ": FAILED");
  return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided);
  int failed = 0;
  {
    const auto session = rumble::fem::PetscSession::get();
    failed += empty_rank_refused(MPI_COMM_WORLD);
    failed += halo_as_estimated(MPI_COMM_WORLD);
  }
  int any = 0;
  MPI_Allreduce(&failed, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();  // (the session's PETSc is left to the process's end: petsc_session.hpp)
  return any == 0 ? 0 : 1;
}
