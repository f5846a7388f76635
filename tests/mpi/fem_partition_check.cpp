// The FEM soil's mesh split over the ranks of mpirun (plugins/soils/fem/distributed; issue #33),
// checked against one process's operator on the same mesh: a Kuhn box partitioned by DMPlex,
// each rank's K and mass assembled from its part (part_stiffness.hpp), and the distributed
// product gathered on rank 0 against CsrOperator's on the whole mesh:
//   - every node of the mesh is owned by exactly one rank, and every tetrahedron is on one rank;
//   - the summed mass equals the whole mesh's to 1e-14;
//   - (K + S) x, K read in double and in single precision, equals one process's to 1e-13 of its
//     largest entry: in single precision only because each entry between shared nodes is summed
//     whole before it is rounded (summed in pieces, the rounding of each piece would leave
//     differences near 6e-8);
//   - the step's product (stepped_product, on 2 threads) hands every node over once, with the
//     same value as the product above, and every ghost holds its owner's value bit for bit;
//   - the same mesh is split alike twice (and so run after run).
// usage: mpirun -n N fem_partition_check   (exit code 0: all held; 1: a check failed)
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "distributed/distributed_operator.hpp"
#include "distributed/mesh_partition.hpp"
#include "distributed/part_stiffness.hpp"
#include "fem_settings.hpp"
#include "mesh/kuhn_box.hpp"
#include "operator/csr_operator.hpp"
#include "operator/elasticity.hpp"
#include "statics/petsc_session.hpp"

namespace {

using namespace rumble::fem;

int rank_of(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}

// A smooth-free test vector from each node's number in the whole mesh (the same on every rank).
double value_at(std::int32_t global, int c) {
  return std::sin(0.37 * global + 1.3 * c) + 0.1 * c;
}

// Counts failures; prints each on rank 0.
struct Checks {
  int failed = 0;
  void expect(bool ok, const char* what, double value) {
    if (ok) return;
    ++failed;
    std::printf("fem_partition_check: FAILED %s (%g)\n", what, value);
  }
};

// max |a - b| / max |b|.
double relative(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

void check_ownership(MPI_Comm comm, const MeshPartition& part, Checks& checks) {
  std::vector<int> owned(static_cast<std::size_t>(part.global_nodes), 0), sum(owned.size(), 0);
  for (std::int32_t i = 0; i < part.nodes(); ++i)
    if (part.owns(i, rank_of(comm))) owned[part.global[i]] = 1;
  MPI_Reduce(owned.data(), sum.data(), static_cast<int>(owned.size()), MPI_INT, MPI_SUM, 0, comm);
  long long tets = static_cast<long long>(part.mesh.tets.size()), all = 0;
  MPI_Reduce(&tets, &all, 1, MPI_LONG_LONG, MPI_SUM, 0, comm);
  if (rank_of(comm) != 0) return;
  int wrong = 0;
  for (int s : sum) wrong += s != 1 ? 1 : 0;
  checks.expect(wrong == 0, "every node owned by exactly one rank", wrong);
  checks.expect(all == part.global_tetrahedra, "every tetrahedron on one rank",
                static_cast<double>(all));
}

// The step's product through NodeProducts on 2 threads, every node once.
Eigen::VectorXd stepped(const DistributedOperator& op, const Eigen::VectorXd& x, int& twice) {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(x.size());
  std::vector<int> seen(static_cast<std::size_t>(op.nodes()), 0);
  const auto finish = [&](std::int64_t i, const double* p) {
    seen[i] += 1;
    for (int c = 0; c < 3; ++c) y[3 * i + c] = p[c];
  };
  NodeProductsOf take(finish);
#pragma omp parallel num_threads(2)
  op.stepped_product(x.data(), take);
  twice = 0;
  for (int s : seen) twice += s != 1 ? 1 : 0;
  return y;
}

int check(MPI_Comm comm, StepPrecision precision, std::vector<std::int32_t>& nodes) {
  Checks checks;
  const bool root = rank_of(comm) == 0;
  const FemSettings settings =
      read_settings(R"({"E": 155e6, "nu": 0.3, "rho": 1800})");  // the medium soil
  const TetMesh whole = kuhn_box(12, 10, 8, 0.5);
  MeshPartition part = partition_mesh(comm, root ? &whole : nullptr);
  nodes = part.global;
  check_ownership(comm, part, checks);
  CsrMatrix K = assemble_stiffness(part.mesh, settings);
  complete_shared_entries(part, K, comm);
  Eigen::VectorXd mass = lumped_mass(part.mesh, settings);
  complete_mass(part, mass);
  Eigen::VectorXd x(3 * part.nodes());
  for (std::int32_t i = 0; i < part.nodes(); ++i)
    for (int c = 0; c < 3; ++c) x[3 * i + c] = value_at(part.global[i], c);
  const DistributedOperator op(std::move(K), mass, {}, false, std::vector<char>(part.nodes(), 0), 2,
                               precision, part.shared, *part.halo);
  Eigen::VectorXd y;
  op.stepped_stiffness_times(x, y, false);
  int twice = 0;
  const Eigen::VectorXd handed = stepped(op, x, twice);
  checks.expect(twice == 0, "stepped_product hands every node over once", twice);
  checks.expect(handed == y, "stepped_product equals the product", relative(handed, y));
  Eigen::VectorXd ghosts = y;  // each ghost's value replaced by its owner's
  part.halo->to_leaves(y.data(), ghosts.data(), 3);
  checks.expect(ghosts == y, "every ghost holds its owner's product", relative(ghosts, y));
  const Eigen::Index n = root ? whole.dof_count() : 0;
  Eigen::VectorXd y_whole = Eigen::VectorXd::Zero(n), mass_whole = Eigen::VectorXd::Zero(n / 3);
  part.from_root->copy_to_roots(y.data(), y_whole.data(), 3);
  part.from_root->copy_to_roots(mass.data(), mass_whole.data(), 1);
  if (root) {
    const CsrOperator one(assemble_stiffness(whole, settings), lumped_mass(whole, settings), {},
                          false, std::vector<char>(whole.node_count(), 0), 1, precision);
    Eigen::VectorXd x_whole(n), y_one;
    for (std::int32_t g = 0; g < whole.node_count(); ++g)
      for (int c = 0; c < 3; ++c) x_whole[3 * g + c] = value_at(g, c);
    one.stepped_stiffness_times(x_whole, y_one, false);
    checks.expect(relative(mass_whole, one.mass()) < 1e-14, "mass as one process's",
                  relative(mass_whole, one.mass()));
    checks.expect(relative(y_whole, y_one) < 1e-13, "K x as one process's",
                  relative(y_whole, y_one));
    std::printf(
        "fem_partition_check (%s): %lld nodes, %lld tetrahedra; rank 0 holds %d nodes "
        "(%d shared); K x within %.2g of one process's, mass within %.2g\n",
        precision == StepPrecision::kSingle ? "single" : "double",
        static_cast<long long>(part.global_nodes), static_cast<long long>(part.global_tetrahedra),
        part.nodes(), part.shared, relative(y_whole, y_one), relative(mass_whole, one.mass()));
  }
  int failed = 0;
  MPI_Allreduce(&checks.failed, &failed, 1, MPI_INT, MPI_MAX, comm);
  return failed;
}

}  // namespace

int main(int argc, char** argv) {
  // MPI as the engine starts it (one thread calls MPI at a time, the product's master here);
  // PETSc then neither starts nor finalises it.
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided);
  int failed = 0;
  {
    const auto session = rumble::fem::PetscSession::get();
    std::vector<std::int32_t> first, second;
    failed += check(MPI_COMM_WORLD, StepPrecision::kDouble, first);
    failed += check(MPI_COMM_WORLD, StepPrecision::kSingle, second);
    // The split repeats (PT-Scotch on one thread from a fixed seed: mesh_partition.cpp).
    int differs = first != second ? 1 : 0, any = 0;
    MPI_Allreduce(&differs, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    if (any != 0 && rank_of(MPI_COMM_WORLD) == 0)
      std::printf("fem_partition_check: FAILED the same mesh split twice alike\n");
    failed += any;
  }
  MPI_Finalize();  // (the session's PETSc is left to the process's end: petsc_session.hpp)
  return failed == 0 ? 0 : 1;
}
