// The soil operator's back end on one rank's part of the mesh (issue #33;
// docs/decisions/0012-distributed-soil.md; soil_operator.hpp has the rule for back ends): K's
// rows of the part's nodes (part_stiffness.hpp), the whole mass and boundary blocks of each of
// its nodes, and the halo (mesh_partition.hpp) that sums the shared nodes' products over the
// ranks.
//
// The step reads the part's K by its upper blocks (operator/symmetric_blocks.hpp, one process's
// kernel and threads unchanged; docs/fem-soil.md §8): each block between two of the part's
// nodes once, used for both. The part's K is symmetric (part_stiffness.hpp) and its blocks are
// taken in one process's node order (the shared and interior nodes merged; x gathered into that
// order for each product), so every interior node's product sums the same terms in the same
// order as one process's and equals it to the bit: only the shared nodes' products, summed over
// the ranks, differ by rounding. (Taken in the part's own order, the shared nodes first, the
// interior nodes next to them summed in another order, and fem_small.json's velocity on 2 ranks
// drifted 4.6e-12 from one process's by 30 ms, against 1e-12 asked; §8.)
//
// The step's product (stepped_product): the interior's products handed to the step as they
// come, the shared nodes' kept; then their sums over the ranks (PETSc's star forest: each
// ghost's product added to its owner's) and the owners' complete products copied back to the
// ghosts (a second exchange of the same nodes) before the shared nodes are handed over.
// Every rank then steps its owned and ghost nodes alike from the same complete product, mass,
// blocks and force, so the copies of a node stay equal bit for bit and the step needs no
// exchange of its own. The explicit step (time/explicit_solver.hpp) runs unchanged on it.
//
// K's compressed rows (in double: GAMG's matrix) are kept until release_stiffness, and built
// again (collectively) when next asked for. The product in double (stiffness_times: the
// geometric multigrid's fine level on the ranks) reads them while they are held, and without
// them forms each of the part's tetrahedra's products from its nodes (element_stiffness.hpp):
// the statics need not hold the rows (docs/fem-soil.md §8, "K without its rows").
//
// Every product is collective: all ranks call it, in the same order. None leaves a rank alone
// inside an exchange: the halo's buffers are made with the partition
// (StarForest::make_exchange_buffers), so the step's product allocates nothing; stiffness_times
// makes its exchanges even when this rank's part of the product fails (K's rows built again), then
// throws, for its caller to agree on (geometric_rank_statics.cpp, rank_agreement.hpp).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "distributed/mesh_partition.hpp"
#include "distributed/star_forest.hpp"
#include "distributed/whole_rows.hpp"
#include "operator/boundary_blocks.hpp"
#include "operator/csr_matrix.hpp"
#include "operator/element_stiffness.hpp"
#include "operator/soil_operator.hpp"
#include "operator/symmetric_blocks.hpp"

namespace rumble::fem {

class DistributedOperator final : public SoilOperator {
 public:
  /// K: the part's rows (part_stiffness.hpp); elements: the same K's product from the part's
  /// tetrahedra; mass, boundary, fixed: per local node, whole; part: the partition (its halo
  /// over the nodes [0, part.shared), its owners and whole numbers; kept alive by the caller);
  /// comm: its ranks.
  DistributedOperator(CsrMatrix K, ElementStiffness elements, Eigen::VectorXd mass,
                      std::vector<BoundaryNode> boundary, bool springs, std::vector<char> fixed,
                      unsigned threads, StepPrecision precision, const MeshPartition& part,
                      MPI_Comm comm);

  void set_threads(unsigned threads) override;
  void stiffness_times(const Eigen::VectorXd& x, Eigen::VectorXd& y,
                       bool with_springs) const override {
    times(x, y, with_springs, false);
  }
  void stepped_stiffness_times(const Eigen::VectorXd& x, Eigen::VectorXd& y,
                               bool with_springs) const override {
    times(x, y, with_springs, true);
  }
  void stepped_product(const double* x, NodeProducts& take) const override;
  StepPrecision precision() const override {
    return single_blocks_ ? StepPrecision::kSingle : StepPrecision::kDouble;
  }
  /// The part's rows (not K's whole rows at the shared nodes). Collective where they were
  /// released (every rank builds its own again): every rank calls it then, in the same order.
  const CsrMatrix& stiffness() const override;
  /// From the part's tetrahedra (the rows not built again): this rank's part of K's diagonal.
  Eigen::VectorXd stiffness_diagonal() const override { return elements_.diagonal(); }
  std::size_t bytes() const override;
  /// The bytes of K the step reads (its upper blocks, their indices and the parts' lists).
  std::size_t stepped_bytes() const {
    return single_blocks_ ? single_blocks_->bytes() : double_blocks_->bytes();
  }
  /// `assemble` builds the part's rows again (collective: part_stiffness.hpp's, the same to the
  /// bit); from then on release_stiffness frees them.
  void set_stiffness_source(std::function<CsrMatrix()> assemble) override {
    assemble_ = std::move(assemble);
  }
  /// Frees the rows (with a source) and the element product's sorted tetrahedra (made again at
  /// its next product): what the statics' products hold, once they are done.
  void release_stiffness() const override {
    if (assemble_) K_.reset();
    elements_.release();
  }
  bool holds_stiffness() const override { return K_.has_value(); }

  std::int32_t shared() const { return shared_; }

  /// Over the nodes this rank owns, then the ranks' sums added in rank order (an all-gather):
  /// every rank gets the same value, run after run.
  double dot(const Eigen::VectorXd& x, const Eigen::VectorXd& y,
             const double* node_weight) const override;
  /// Over the nodes this rank owns, then in rank order (as dot).
  double sum_over_nodes(const std::vector<double>& per_node) const override;
  double max_over_nodes(const std::vector<double>& per_node) const override;
  /// The part's upper blocks as the step reads them, in the part's own node numbers.
  void for_each_step_block(const BlockVisit& visit) const override;
  /// The part's, completed over the ranks at the shared nodes (whole_rows.hpp).
  std::vector<double> row_magnitude_sums() const override {
    std::vector<double> sums = SoilOperator::row_magnitude_sums();
    sum_shared_nodes(sums.data(), 3);  // (each entry whole on one rank: part_stiffness.hpp)
    return sums;
  }
  std::vector<std::int32_t> flagged_neighbours(const std::vector<char>& flag) const override {
    return whole_flagged_neighbours(part_, *this, flag, comm_);
  }
  std::int64_t whole_node(std::int64_t i) const override { return global_[i]; }
  bool spans_ranks() const override { return true; }
  std::int32_t shared_nodes() const override { return shared_; }
  /// (a failed exchange stops every rank: it is called inside the step's OpenMP region)
  void sum_shared_nodes(double* values, int width) const override;

  /// From now on this rank's part of stiffness_times and stepped_stiffness_times (the statics'
  /// products, not the step's) throws std::runtime_error(why) (its exchanges still made):
  /// tests/mpi's product failure on one rank (RUMBLE_FEM_FAIL_RANK_AT).
  void fail_products_on_purpose(std::string why) { failing_ = std::move(why); }

 private:
  /// y = K x + S x, summed over the ranks at the shared nodes, 0 on fixed nodes.
  void times(const Eigen::VectorXd& x, Eigen::VectorXd& y, bool with_springs, bool stepped) const;
  /// x into ordered_x_ (one process's order), this thread's share; a barrier at the end.
  void gather_x(const double* x) const;
  /// The blocks' product, by the step's precision: finish(i, product) for each local node i, by
  /// the thread whose part holds it. Called by every thread of a team; no barrier at the end.
  template <class Finish>
  void blocks_times(const double* x, Finish&& finish) const;

  mutable std::optional<CsrMatrix> K_;  // (a cache: released between the statics)
  std::function<CsrMatrix()> assemble_;
  ElementStiffness elements_;  // (K x without the rows)
  // The part's upper blocks as the step reads them: rounded to float, or in double (one of two).
  std::optional<SymmetricBlocks<float>> single_blocks_;
  std::optional<SymmetricBlocks<double>> double_blocks_;
  mutable std::vector<NodeSum> scratch_;  // the blocks' pending sums; zero between products
  std::int32_t shared_;
  const MeshPartition& part_;
  const StarForest& halo_;
  const std::vector<std::int32_t>& global_;  // per local node: its node in the whole mesh
  std::vector<char> owned_;                  // per local node: this rank owns it
  MPI_Comm comm_;
  mutable std::vector<double> shared_products_;  // 3 per shared node
  std::vector<std::int32_t> order_;              // the local nodes in one process's order
  mutable std::vector<double> ordered_x_;        // the product's x in that order
  std::string failing_;                          // (fail_products_on_purpose's)
};

}  // namespace rumble::fem
