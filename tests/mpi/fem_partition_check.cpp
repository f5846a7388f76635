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
//   - the products' halo exchanges allocate nothing in PETSc (the partition made their buffers,
//     so no rank can fail alone inside one: StarForest::make_exchange_buffers);
//   - the step's product (stepped_product, on 2 threads) hands every node over once, with the
//     same value as the product above, and every ghost holds its owner's value bit for bit; it
//     reads the part's upper blocks, under 0.7 of the bytes of its whole rows; each node not
//     shared has one process's product bit for bit (its sums in one process's node order; taken
//     in the part's order, 156 of 1187 differed on 2 ranks, and whole runs drifted);
//   - the same mesh is split alike twice (and so run after run);
//   - the same with a coarse box refined once and twice on the ranks after the split
//     (refined_partition.hpp): each fine node owned once, every fine tetrahedron on one rank,
//     the mass and K x against one process's refinement of the whole box (its nodes put in the
//     ranks' numbering, numbered_refinement.hpp), ghosts equal to their owners; and what each
//     rank builds from its refined part (below) as one process builds it on the refined box;
//   - what each rank builds from its own part (distributed/part_pieces.hpp) equals what one
//     process builds on the whole mesh: the boundary blocks (area, normal, dashpots, springs)
//     at every node a rank holds, the far field's rows and mean distance, to 1e-14 (a shared
//     node's faces summed in another order); the footprints' weights (their faces weighed in the
//     whole mesh's order) and the receivers' tetrahedra and weights (the same tetrahedron chosen,
//     ties included) bit for bit;
//   - what the local time stepping's choice reads of K's whole rows (whole_rows.hpp): each
//     node's magnitude sums within 1e-14 of one process's, its flagged neighbours exactly, the
//     same at every copy of a node;
//   - the stable step's largest eigenvalue by Lanczos over the ranks (sums in rank order) equals
//     one process's to 1e-9, its own tolerance, and is the same on every rank.
// usage: PETSC_OPTIONS=-malloc_dump mpirun -n N fem_partition_check   (exit code 0: all held;
// 1: a check failed)
#include <omp.h>
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <numeric>
#include <vector>

#include "boundary/absorbing_boundary.hpp"
#include "boundary/static_far_field.hpp"
#include "distributed/distributed_operator.hpp"
#include "distributed/mesh_partition.hpp"
#include "distributed/part_pieces.hpp"
#include "distributed/part_stiffness.hpp"
#include "distributed/refined_partition.hpp"
#include "fem_settings.hpp"
#include "mesh/kuhn_box.hpp"
#include "mesh/node_order.hpp"
#include "mesh/numbered_refinement.hpp"
#include "operator/csr_operator.hpp"
#include "operator/elasticity.hpp"
#include "statics/petsc_session.hpp"
#include "time/explicit_solver.hpp"

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

// The bytes PETSc holds now (its tracing malloc, which the test's PETSC_OPTIONS -malloc_dump
// turns on; main checks that it is on).
double petsc_bytes() {
  PetscLogDouble bytes = 0.0;
  PetscMallocGetCurrentUsage(&bytes);
  return bytes;
}

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

/// The box the checks split (a Kuhn box of 0.5 m cubes), with this rank's part: refine 0 split as
/// is; refine > 0 a box twice as coarse per level, split, and each part refined `refine` times
/// after the split. whole: the mesh one process steps (the refined box in the ranks' numbering).
struct SplitBox {
  TetMesh whole;
  MeshPartition part;
};
SplitBox split_box(MPI_Comm comm, int refine) {
  const bool root = rank_of(comm) == 0;
  const TetMesh coarse = refine == 0 ? kuhn_box(12, 10, 8, 0.5) : kuhn_box(6, 5, 4, 1.0);
  MeshPartition part =
      refine == 0
          ? partition_mesh(comm, root ? &coarse : nullptr)
          : refine_partition(comm, partition_mesh(comm, root ? &coarse : nullptr, true), refine);
  return {refine == 0 ? coarse : refined_whole(coarse, refine), std::move(part)};
}

// One process's stepped K x on `whole` at value_at, in whole's numbering: its CsrOperator on
// the mesh in one process's node order (refined: the Morton order, ties by number, fem_layout's;
// else whole's own).
Eigen::VectorXd one_process_product(const TetMesh& whole, const FemSettings& settings,
                                    StepPrecision precision, bool refined) {
  std::vector<std::int32_t> order(static_cast<std::size_t>(whole.node_count()));  // new -> old
  std::iota(order.begin(), order.end(), 0);
  TetMesh mesh = whole;
  if (refined) {
    const std::vector<std::int64_t> number(order.begin(), order.end());
    order = numbered_spatial_order(whole.nodes, number, whole.nodes.rowwise().minCoeff(),
                                   whole.nodes.rowwise().maxCoeff());
    renumber_nodes(mesh, order);
  }
  const CsrOperator one(assemble_stiffness(mesh, settings), lumped_mass(mesh, settings), {}, false,
                        std::vector<char>(mesh.node_count(), 0), 1, precision);
  Eigen::VectorXd x(whole.dof_count()), y, y_whole(whole.dof_count());
  for (std::size_t k = 0; k < order.size(); ++k)
    for (int c = 0; c < 3; ++c) x[3 * k + c] = value_at(order[k], c);
  one.stepped_stiffness_times(x, y, false);
  for (std::size_t k = 0; k < order.size(); ++k)
    y_whole.segment<3>(3 * order[k]) = y.segment<3>(3 * k);
  return y_whole;
}

// What the local time stepping's choice reads of K's whole rows (SoilOperator::
// row_magnitude_sums, flagged_neighbours: distributed/whole_rows.hpp) at every rank's nodes,
// gathered on rank 0, against one process's operator on the whole mesh in the same precision:
// the magnitude sums to 1e-14 of the largest (the shared entries summed in another order) and
// the flagged neighbours (flags from each node's number) exactly.
void check_whole_rows(MPI_Comm comm, const DistributedOperator& op, const MeshPartition& part,
                      const TetMesh& whole, const FemSettings& settings, StepPrecision precision,
                      Checks& checks) {
  const auto flag_of = [](std::int32_t global) { return static_cast<char>(global % 3 == 0); };
  std::vector<char> flag(static_cast<std::size_t>(part.nodes()));
  for (std::int32_t i = 0; i < part.nodes(); ++i) flag[i] = flag_of(part.global[i]);
  const std::vector<double> sums = op.row_magnitude_sums();
  const std::vector<std::int32_t> counted = op.flagged_neighbours(flag);
  std::vector<double> counts(counted.begin(), counted.end());
  const bool root = rank_of(comm) == 0;
  const std::int64_t n = root ? whole.node_count() : 0;
  std::vector<double> sums_whole(static_cast<std::size_t>(3 * n), -1.0);
  std::vector<double> counts_whole(static_cast<std::size_t>(n), -1.0);
  part.from_root->copy_to_roots(sums.data(), sums_whole.data(), 3);
  part.from_root->copy_to_roots(counts.data(), counts_whole.data(), 1);
  // Every copy of a node holds the same values (the counts exactly, the sums to the bit).
  std::vector<double> ghosts = sums, ghost_counts = counts;
  part.halo->to_leaves(sums.data(), ghosts.data(), 3);
  part.halo->to_leaves(counts.data(), ghost_counts.data(), 1);
  checks.expect(ghosts == sums && ghost_counts == counts,
                "every copy of a node has its owner's whole-row sums and counts", 0.0);
  if (!root) return;
  const CsrOperator one(assemble_stiffness(whole, settings), lumped_mass(whole, settings), {},
                        false, std::vector<char>(static_cast<std::size_t>(n), 0), 1, precision);
  std::vector<char> whole_flag(static_cast<std::size_t>(n));
  for (std::int32_t g = 0; g < n; ++g) whole_flag[g] = flag_of(g);
  const std::vector<double> one_sums = one.row_magnitude_sums();
  const std::vector<std::int32_t> one_counts = one.flagged_neighbours(whole_flag);
  // (and one process's own two readings of K agree: its rows in double against the step's
  // blocks, to the step's rounding)
  const std::vector<double> rows = one.stiffness().magnitude_sums();
  double read = 0.0;
  for (std::size_t k = 0; k < rows.size(); ++k)
    read = std::max(read, std::abs(rows[k] - one_sums[k]) / rows[k]);
  checks.expect(read <= (precision == StepPrecision::kSingle ? 6e-8 : 1e-15),
                "the step's blocks' magnitude sums as K's rows', to the step's rounding", read);
  checks.expect(
      one.flagged_neighbours(whole_flag) == one.stiffness().flagged_neighbours(whole_flag),
      "the step's blocks' pattern as K's rows'", 0.0);
  const double largest = *std::max_element(one_sums.begin(), one_sums.end());
  double differ = 0.0;
  for (std::size_t k = 0; k < one_sums.size(); ++k)
    differ = std::max(differ, std::abs(sums_whole[k] - one_sums[k]) / largest);
  int wrong = 0;
  for (std::int64_t g = 0; g < n; ++g) wrong += counts_whole[g] != one_counts[g] ? 1 : 0;
  checks.expect(differ <= 1e-14, "K's whole rows' magnitude sums as one process's", differ);
  checks.expect(wrong == 0, "K's whole rows' flagged neighbours as one process's", wrong);
  std::printf(
      "fem_partition_check: K's whole rows on the ranks: magnitude sums within %.2g of one "
      "process's, flagged neighbours %d of %lld nodes wrong\n",
      differ, wrong, static_cast<long long>(n));
}

// refine > 0: a coarser box split, each rank's part refined `refine` times after the split.
int check(MPI_Comm comm, StepPrecision precision, std::vector<std::int32_t>& nodes,
          int refine = 0) {
  Checks checks;
  const bool root = rank_of(comm) == 0;
  const FemSettings settings =
      read_settings(R"({"E": 155e6, "nu": 0.3, "rho": 1800})");  // the medium soil
  auto [whole, part] = split_box(comm, refine);
  nodes = part.global;
  check_ownership(comm, part, checks);
  CsrMatrix K = assemble_stiffness(part.mesh, settings);
  complete_shared_entries(part, K, comm);
  Eigen::VectorXd mass = lumped_mass(part.mesh, settings);
  complete_mass(part, mass);
  Eigen::VectorXd x(3 * part.nodes());
  for (std::int32_t i = 0; i < part.nodes(); ++i)
    for (int c = 0; c < 3; ++c) x[3 * i + c] = value_at(part.global[i], c);
  const DistributedOperator op(std::move(K), ElementStiffness(part.mesh, settings), mass, {}, false,
                               std::vector<char>(part.nodes(), 0), 2, precision, part, comm);
  Eigen::VectorXd y;
  const double petsc_before = petsc_bytes();
  op.stepped_stiffness_times(x, y, false);
  int twice = 0;
  const Eigen::VectorXd handed = stepped(op, x, twice);
  checks.expect(
      petsc_bytes() == petsc_before,
      "the products' exchanges allocate nothing in PETSc (the partition made their buffers)",
      petsc_bytes() - petsc_before);
  checks.expect(twice == 0, "stepped_product hands every node over once", twice);
  checks.expect(handed == y, "stepped_product equals the product", relative(handed, y));
  // The step reads the part's upper blocks: about half the bytes of its whole rows in the
  // step's precision (a value each, an index per block), the shared nodes' blocks into the
  // interior listed again for the interior's parts.
  const double value_bytes = precision == StepPrecision::kSingle ? 4.0 : 8.0;
  const auto nonzeros = static_cast<double>(op.stiffness().nonzeros());
  const double rows = nonzeros * value_bytes + nonzeros / 9.0 * 4.0;
  const double upper = static_cast<double>(op.stepped_bytes()) / rows;
  checks.expect(upper < 0.7, "the step reads about half of the part's rows' bytes", upper);
  check_whole_rows(comm, op, part, whole, settings, precision, checks);
  Eigen::VectorXd ghosts = y;  // each ghost's value replaced by its owner's
  part.halo->to_leaves(y.data(), ghosts.data(), 3);
  checks.expect(ghosts == y, "every ghost holds its owner's product", relative(ghosts, y));
  const Eigen::Index n = root ? whole.dof_count() : 0;
  Eigen::VectorXd y_whole = Eigen::VectorXd::Zero(n), mass_whole = Eigen::VectorXd::Zero(n / 3);
  part.from_root->copy_to_roots(y.data(), y_whole.data(), 3);
  part.from_root->copy_to_roots(mass.data(), mass_whole.data(), 1);
  Eigen::VectorXd shared = Eigen::VectorXd::Zero(part.nodes()), shared_whole = mass_whole;
  shared.head(part.shared).setOnes();  // (every copy of a shared node says so)
  part.from_root->copy_to_roots(shared.data(), shared_whole.data(), 1);
  if (root) {
    const Eigen::VectorXd y_one = one_process_product(whole, settings, precision, refine > 0);
    const Eigen::VectorXd mass_one = lumped_mass(whole, settings);
    checks.expect(relative(mass_whole, mass_one) < 1e-14, "mass as one process's",
                  relative(mass_whole, mass_one));
    checks.expect(relative(y_whole, y_one) < 1e-13, "K x as one process's",
                  relative(y_whole, y_one));
    // Each interior node's product sums one process's terms in one process's order (the
    // blocks in its node order, distributed_operator.hpp): to the bit.
    int differ = 0, interior = 0;
    for (Eigen::Index g = 0; g < n / 3; ++g) {
      if (shared_whole[g] != 0.0) continue;
      ++interior;
      if (y_whole.segment<3>(3 * g) != y_one.segment<3>(3 * g)) ++differ;
    }
    checks.expect(differ == 0, "each interior node's product as one process's, to the bit", differ);
    std::printf(
        "fem_partition_check (%s, refined %d times on the ranks): %lld nodes, %lld tetrahedra; "
        "rank 0 holds %d nodes (%d shared), its step reads %.2f of its rows' bytes; K x within "
        "%.2g of one process's (%d of %d interior nodes not to the bit), mass within %.2g\n",
        precision == StepPrecision::kSingle ? "single" : "double", refine,
        static_cast<long long>(part.global_nodes), static_cast<long long>(part.global_tetrahedra),
        part.nodes(), part.shared, upper, relative(y_whole, y_one), differ, interior,
        relative(mass_whole, mass_one));
  }
  int failed = 0;
  MPI_Allreduce(&checks.failed, &failed, 1, MPI_INT, MPI_MAX, comm);
  return failed;
}

// The pieces' test case: two sleepers' footprints on the box's ground, cell-aligned (the box's
// cells are 0.5 m), and receivers inside, on the ground at a node, and on an edge.
std::vector<rumble::Footprint> box_footprints() {
  return {{2.5, 2.5, 2.0, 1.0}, {4.0, 2.5, 2.0, 1.0}};
}
std::vector<rumble::Probe> box_probes() {
  return {{"inside", 1.3, 1.7, 2.2}, {"on a node", 3.0, 2.5, 0.0}, {"on an edge", 3.0, 2.5, 1.25}};
}

// Every rank's rows (`width` doubles each) on rank 0, in rank order.
std::vector<double> gather_rows(MPI_Comm comm, const std::vector<double>& mine) {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const int count = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(ranks)), starts(counts.size(), 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  for (int r = 1; r < ranks; ++r) starts[r] = starts[r - 1] + counts[r - 1];
  std::vector<double> all(rank_of(comm) == 0 ? starts.back() + counts.back() : 0);
  MPI_Gatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), starts.data(), MPI_DOUBLE,
              0, comm);
  return all;
}

// A boundary node's values: area, normal (3), dashpots (2), spring (9).
constexpr int kBoundaryValues = 15;
void boundary_values(const BoundaryNode& b, double* out) {
  out[0] = b.area;
  for (int c = 0; c < 3; ++c) out[1 + c] = b.normal[c];
  out[4] = b.dashpot_normal;
  out[5] = b.dashpot_tangential;
  for (int k = 0; k < 9; ++k) out[6 + k] = b.spring.data()[k];
}

// Rows keyed by their first value (a whole node, or footprint and node): the largest difference
// of the rest from `whole`'s, relative to each column's largest value; -1 when a key is missing.
double rows_differ(const std::vector<double>& rows,
                   const std::map<double, std::vector<double>>& whole, std::size_t width) {
  std::vector<double> scale(width, 0.0);
  for (const auto& [key, row] : whole)
    for (std::size_t c = 0; c < width; ++c) scale[c] = std::max(scale[c], std::abs(row[c]));
  double worst = 0.0;
  for (std::size_t k = 0; k < rows.size(); k += width + 1) {
    const auto it = whole.find(rows[k]);
    if (it == whole.end()) return -1.0;
    for (std::size_t c = 0; c < width; ++c)
      if (scale[c] > 0.0)
        worst = std::max(worst, std::abs(rows[k + 1 + c] - it->second[c]) / scale[c]);
  }
  return worst;
}

// The boundary blocks each rank built from its part against one process's, at every node a
// rank holds (owned and ghost); every whole boundary node owned once.
void check_boundary(MPI_Comm comm, const MeshPartition& part, const TetMesh& whole,
                    const FemSettings& settings, const std::vector<BoundaryNode>& mine,
                    Checks& checks) {
  std::vector<double> rows;
  long long owned = 0;
  for (const BoundaryNode& b : mine) {
    rows.push_back(part.global[b.node]);
    rows.resize(rows.size() + kBoundaryValues);
    boundary_values(b, rows.data() + rows.size() - kBoundaryValues);
    owned += part.owns(b.node, rank_of(comm)) ? 1 : 0;
  }
  long long all_owned = 0;
  MPI_Reduce(&owned, &all_owned, 1, MPI_LONG_LONG, MPI_SUM, 0, comm);
  const std::vector<double> all = gather_rows(comm, rows);
  if (rank_of(comm) != 0) return;
  std::map<double, std::vector<double>> one;
  for (const BoundaryNode& b : absorbing_boundary(whole, settings, box_footprints())) {
    one[b.node].resize(kBoundaryValues);
    boundary_values(b, one[b.node].data());
  }
  const double differ = rows_differ(all, one, kBoundaryValues);
  checks.expect(all_owned == static_cast<long long>(one.size()),
                "every boundary node owned by one rank", static_cast<double>(all_owned));
  checks.expect(differ >= 0.0 && differ <= 1e-14, "boundary blocks as one process's", differ);
  std::printf("fem_partition_check: %zu boundary nodes, blocks within %.2g of one process's\n",
              one.size(), differ);
}

// The footprints' weights each rank built against one process's, keyed by footprint and node.
void check_weights(MPI_Comm comm, const MeshPartition& part, const TetMesh& whole, Checks& checks) {
  const FootprintWeights mine = part_footprint_weights(comm, part, box_footprints());
  std::vector<double> rows;
  for (std::size_t j = 0; j < mine.size(); ++j)
    for (const NodalWeight& w : mine[j])
      rows.insert(rows.end(), {1e9 * j + part.global[w.node], w.weight});
  const std::vector<double> all = gather_rows(comm, rows);
  if (rank_of(comm) != 0) return;
  std::map<double, std::vector<double>> one;
  const FootprintWeights weights = footprint_weights(whole, box_footprints());
  for (std::size_t j = 0; j < weights.size(); ++j)
    for (const NodalWeight& w : weights[j]) one[1e9 * j + w.node] = {w.weight};
  std::map<double, int> seen;
  for (std::size_t k = 0; k < all.size(); k += 2) seen[all[k]] = 1;
  const double differ = rows_differ(all, one, 1);
  checks.expect(seen.size() == one.size(), "every footprint node on a rank",
                static_cast<double>(seen.size()));
  checks.expect(differ == 0.0, "footprint weights as one process's (bit for bit)", differ);
  std::printf("fem_partition_check: %zu footprint weights within %.2g of one process's\n",
              one.size(), differ);
}

// The far field's rows (per footprint, 3 per node) and mean distance against one process's.
void check_far_field(MPI_Comm comm, const MeshPartition& part, const TetMesh& whole,
                     const FemSettings& settings, const std::vector<BoundaryNode>& mine,
                     Checks& checks) {
  const StaticFarField far(part.mesh, settings, box_footprints(), mine);
  const double distance = boundary_mean_distance(comm, part, mine, box_footprints());
  const auto width = static_cast<std::size_t>(far.loads().cols()) * 3;
  std::vector<double> rows;
  for (std::size_t k = 0; k < far.nodes().size(); ++k) {
    rows.push_back(part.global[far.nodes()[k]]);
    for (Eigen::Index j = 0; j < far.loads().cols(); ++j)
      for (int c = 0; c < 3; ++c)
        rows.push_back(far.loads()(3 * static_cast<Eigen::Index>(k) + c, j));
  }
  const std::vector<double> all = gather_rows(comm, rows);
  if (rank_of(comm) != 0) return;
  const StaticFarField one(whole, settings, box_footprints(),
                           absorbing_boundary(whole, settings, box_footprints()));
  std::map<double, std::vector<double>> by_node;
  for (std::size_t k = 0; k < one.nodes().size(); ++k)
    for (Eigen::Index j = 0; j < one.loads().cols(); ++j)
      for (int c = 0; c < 3; ++c)
        by_node[one.nodes()[k]].push_back(one.loads()(3 * static_cast<Eigen::Index>(k) + c, j));
  const double differ = rows_differ(all, by_node, width);
  const double mean = std::abs(distance - one.mean_distance()) / one.mean_distance();
  checks.expect(differ >= 0.0 && differ <= 1e-14, "far field's rows as one process's", differ);
  checks.expect(mean <= 1e-14, "far field's mean distance as one process's", mean);
  std::printf("fem_partition_check: far field's rows within %.2g, mean distance within %.2g\n",
              differ, mean);
}

// Each receiver's tetrahedron (whole nodes) and weights, from the rank that samples it, against
// locate_probe's on the whole mesh: bit for bit; every receiver sampled once.
void check_probes(MPI_Comm comm, const MeshPartition& part, const TetMesh& whole, Checks& checks) {
  std::vector<double> rows;  // per receiver sampled here: index, 4 nodes, 4 weights
  for (const PartProbe& p : part_probes(comm, part, box_probes())) {
    rows.push_back(static_cast<double>(p.index));
    for (int a = 0; a < 4; ++a) rows.push_back(part.global[p.point.nodes[a]]);
    rows.insert(rows.end(), p.point.weights.begin(), p.point.weights.end());
  }
  const std::vector<double> all = gather_rows(comm, rows);
  if (rank_of(comm) != 0) return;
  std::map<double, std::vector<double>> one;
  const std::vector<rumble::Probe> probes = box_probes();
  for (std::size_t p = 0; p < probes.size(); ++p) {
    const rumble::Probe& q = probes[p];
    const ProbePoint point = locate_probe(whole, q.x, q.y, q.depth, q.name);
    one[static_cast<double>(p)].assign(point.nodes.begin(), point.nodes.end());
    one[static_cast<double>(p)].insert(one[static_cast<double>(p)].end(), point.weights.begin(),
                                       point.weights.end());
  }
  const double differ = rows_differ(all, one, 8);
  checks.expect(all.size() == 9 * one.size(), "every receiver sampled by one rank",
                static_cast<double>(all.size()));
  checks.expect(differ == 0.0, "receivers' places as one process's (bit for bit)", differ);
  std::printf("fem_partition_check: %zu receivers' places within %.2g of one process's\n",
              one.size(), differ);
}

// The largest eigenvalue of M^-1 (K + S) by Lanczos over the ranks against one process's.
void check_stable_step(MPI_Comm comm, MeshPartition& part, const TetMesh& whole,
                       const FemSettings& settings, std::vector<BoundaryNode> mine,
                       Checks& checks) {
  CsrMatrix K = assemble_stiffness(part.mesh, settings);
  complete_shared_entries(part, K, comm);
  Eigen::VectorXd mass = lumped_mass(part.mesh, settings);
  complete_mass(part, mass);
  const ExplicitSolver ranks(
      std::make_unique<DistributedOperator>(
          std::move(K), ElementStiffness(part.mesh, settings), std::move(mass), std::move(mine),
          true, std::vector<char>(part.nodes(), 0), 1, StepPrecision::kDouble, part, comm),
      0.0, 0.0);
  const double lambda = ranks.largest_eigenvalue();
  double lowest = 0.0, highest = 0.0;
  MPI_Allreduce(&lambda, &lowest, 1, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(&lambda, &highest, 1, MPI_DOUBLE, MPI_MAX, comm);
  if (rank_of(comm) != 0) return;
  const ExplicitSolver one(assemble_stiffness(whole, settings), lumped_mass(whole, settings),
                           absorbing_boundary(whole, settings, box_footprints()), true,
                           std::vector<char>(whole.node_count(), 0), 0.0, 0.0, 1);
  const double differ = std::abs(lambda - one.largest_eigenvalue()) / one.largest_eigenvalue();
  checks.expect(lowest == highest, "the same eigenvalue on every rank", highest - lowest);
  checks.expect(differ <= 1e-9, "largest eigenvalue as one process's (to 1e-9)", differ);
  std::printf(
      "fem_partition_check: largest eigenvalue %.12g on the ranks (%d Lanczos iterations), "
      "%.12g on one process (%d), within %.2g\n",
      lambda, ranks.eigen_iterations(), one.largest_eigenvalue(), one.eigen_iterations(), differ);
}

// What each rank builds from its part (part_pieces.hpp) against one process's on the whole mesh.
// refine 1: the same box as twice as coarse a box refined once on the ranks after the split.
int check_pieces(MPI_Comm comm, int refine = 0) {
  Checks checks;
  const FemSettings settings = read_settings(R"({"E": 155e6, "nu": 0.3, "rho": 1800})");
  auto [whole, part] = split_box(comm, refine);
  const std::vector<BoundaryNode> mine = part_boundary(part, settings, box_footprints());
  check_boundary(comm, part, whole, settings, mine, checks);
  check_weights(comm, part, whole, checks);
  check_far_field(comm, part, whole, settings, mine, checks);
  check_probes(comm, part, whole, checks);
  check_stable_step(comm, part, whole, settings, mine, checks);
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
    PetscBool traced = PETSC_FALSE;
    PetscMallocGetDebug(&traced, nullptr, nullptr);
    if (!traced) {
      if (rank_of(MPI_COMM_WORLD) == 0)
        std::printf(
            "fem_partition_check: FAILED PETSc's malloc is not traced: run it with "
            "PETSC_OPTIONS=-malloc_dump, as its test does\n");
      ++failed;
    }
    std::vector<std::int32_t> first, second;
    failed += check(MPI_COMM_WORLD, StepPrecision::kDouble, first);
    failed += check(MPI_COMM_WORLD, StepPrecision::kSingle, second);
    // The split repeats (PT-Scotch on one thread from a fixed seed: mesh_partition.cpp).
    int differs = first != second ? 1 : 0, any = 0;
    MPI_Allreduce(&differs, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    if (any != 0 && rank_of(MPI_COMM_WORLD) == 0)
      std::printf("fem_partition_check: FAILED the same mesh split twice alike\n");
    failed += any;
    failed += check_pieces(MPI_COMM_WORLD);
    for (int levels = 1; levels <= 2; ++levels)
      failed += check(MPI_COMM_WORLD, StepPrecision::kSingle, second, levels);
    failed += check_pieces(MPI_COMM_WORLD, 1);
  }
  MPI_Finalize();  // (the session's PETSc is left to the process's end: petsc_session.hpp)
  return failed == 0 ? 0 : 1;
}
