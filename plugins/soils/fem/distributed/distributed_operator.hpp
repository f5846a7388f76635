// The soil operator's back end on one rank's part of the mesh (issue #33;
// docs/decisions/0012-distributed-soil.md; soil_operator.hpp has the rule for back ends): K's
// rows of the part's nodes (part_stiffness.hpp), the whole mass and boundary blocks of each of
// its nodes, and the halo (mesh_partition.hpp) that sums the shared nodes' products over the
// ranks.
//
// The step's product (stepped_product): the shared nodes' rows first; their sums over the ranks
// begin (PETSc's star forest: each ghost's row added to its owner's) while the interior's rows
// are computed and handed to the step, then end, and the owners' complete products are copied
// back to the ghosts (a second exchange of the same nodes) before the shared nodes are handed
// over. Every rank then steps its owned and ghost nodes alike from the same complete product,
// mass, blocks and force, so the copies of a node stay equal bit for bit and the step needs no
// exchange of its own. The explicit step (time/explicit_solver.hpp) runs unchanged on it.
//
// Every product is collective: all ranks call it, in the same order.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "distributed/mesh_partition.hpp"
#include "distributed/star_forest.hpp"
#include "operator/boundary_blocks.hpp"
#include "operator/csr_matrix.hpp"
#include "operator/soil_operator.hpp"

namespace rumble::fem {

class DistributedOperator final : public SoilOperator {
 public:
  /// K: the part's rows (part_stiffness.hpp); mass, boundary, fixed: per local node, whole;
  /// part: the partition (its halo over the nodes [0, part.shared), its owners and whole
  /// numbers; kept alive by the caller); comm: its ranks.
  DistributedOperator(CsrMatrix K, Eigen::VectorXd mass, std::vector<BoundaryNode> boundary,
                      bool springs, std::vector<char> fixed, unsigned threads,
                      StepPrecision precision, const MeshPartition& part, MPI_Comm comm);

  void set_threads(unsigned threads) override { threads_ = threads < 1 ? 1 : threads; }
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
    return single_.empty() ? StepPrecision::kDouble : StepPrecision::kSingle;
  }
  /// The part's rows (not K's whole rows at the shared nodes).
  const CsrMatrix& stiffness() const override { return K_; }
  std::size_t bytes() const override;

  std::int32_t shared() const { return shared_; }

  /// Over the nodes this rank owns, then the ranks' sums added in rank order (an all-gather):
  /// every rank gets the same value, run after run.
  double dot(const Eigen::VectorXd& x, const Eigen::VectorXd& y,
             const double* node_weight) const override;
  std::int64_t whole_node(std::int64_t i) const override { return global_[i]; }

 private:
  /// Node i's rows of the part's K times x (K as the step reads it when stepped).
  void rows_times(std::int32_t i, const double* x, double out[3], bool stepped) const;
  /// y = K x + S x, summed over the ranks at the shared nodes, 0 on fixed nodes.
  void times(const Eigen::VectorXd& x, Eigen::VectorXd& y, bool with_springs, bool stepped) const;

  CsrMatrix K_;
  std::vector<float> single_;  // K's values rounded to float (StepPrecision::kSingle), else empty
  std::int32_t shared_;
  const StarForest& halo_;
  const std::vector<std::int32_t>& global_;  // per local node: its node in the whole mesh
  std::vector<char> owned_;                  // per local node: this rank owns it
  MPI_Comm comm_;
  mutable std::vector<double> shared_products_;  // 3 per shared node
};

}  // namespace rumble::fem
