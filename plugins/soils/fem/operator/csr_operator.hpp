// The soil operator's first back end (soil_operator.hpp): K in compressed rows (csr_matrix.hpp)
// for the products in double and the direct solvers, and K's upper 3 x 3 blocks
// (symmetric_blocks.hpp) in the step's precision for the step's and the iterations' products,
// split over OpenMP threads by contiguous node ranges. One machine, shared memory.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <mutex>
#include <optional>
#include <vector>

#include "operator/boundary_blocks.hpp"
#include "operator/csr_matrix.hpp"
#include "operator/soil_operator.hpp"
#include "operator/symmetric_blocks.hpp"

namespace rumble::fem {

class CsrOperator final : public SoilOperator {
 public:
  /// K: elastic stiffness; mass per node [kg]; boundary blocks (springs used when `springs`);
  /// fixed: per node, never moves; precision: how the step's products read K.
  CsrOperator(CsrMatrix K, Eigen::VectorXd mass, std::vector<BoundaryNode> boundary, bool springs,
              std::vector<char> fixed, unsigned threads, StepPrecision precision);

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
  const CsrMatrix& stiffness() const override;
  /// From the step's upper blocks (no rows assembled).
  void for_each_step_block(const BlockVisit& visit) const override;
  std::size_t bytes() const override;
  /// The kernel of the step's product (symmetric_blocks.hpp): by default the SIMD one where the
  /// processor runs it; the portable one on request (benchmarks, tests).
  BlockKernel block_kernel() const {
    return single_blocks_ ? single_blocks_->kernel() : double_blocks_->kernel();
  }
  void set_block_kernel(BlockKernel kernel);
  void set_stiffness_source(std::function<CsrMatrix()> assemble) override;
  void release_stiffness() const override;
  CsrMatrix take_stiffness() const override;
  bool holds_stiffness() const override;

  /// stepped_product with the caller's finish inlined, for an integrator that knows this back
  /// end (ExplicitSolver): for each node i, finish(i, out) with out = (K x) at node i, K as the
  /// step reads it (its upper blocks in the step's precision). Called by every thread of a team;
  /// no barrier at the end (symmetric_blocks.hpp).
  template <class Finish>
  void fused_product(const double* x, Finish&& finish) const {
    if (single_blocks_)
      single_blocks_->multiply(x, product_scratch_.data(), finish);
    else
      double_blocks_->multiply(x, product_scratch_.data(), finish);
  }

 private:
  /// y = K x + S x with K read as the step reads it (stepped) or in double.
  void times(const Eigen::VectorXd& x, Eigen::VectorXd& y, bool with_springs, bool stepped) const;

  // K's rows: held from construction, freed by release/take when a source can build them again
  // (mutable: a cache of the same K, which stiffness() refills; the mutex guards the refill).
  mutable std::optional<CsrMatrix> K_;
  std::function<CsrMatrix()> assemble_;
  mutable std::mutex K_mutex_;
  // K's upper blocks as the step reads them: rounded to float, or in double (one of the two).
  std::optional<SymmetricBlocks<float>> single_blocks_;
  std::optional<SymmetricBlocks<double>> double_blocks_;
  mutable std::vector<NodeSum> product_scratch_;  // the blocks' product's; zero between products
};

}  // namespace rumble::fem
