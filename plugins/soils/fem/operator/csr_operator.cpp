#include "operator/csr_operator.hpp"

#include <algorithm>
#include <cstdint>
#include <utility>

namespace rumble::fem {

CsrOperator::CsrOperator(CsrMatrix K, Eigen::VectorXd mass, std::vector<BoundaryNode> boundary,
                         bool springs, std::vector<char> fixed, unsigned threads,
                         StepPrecision precision)
    : SoilOperator(std::move(mass), std::move(boundary), springs, std::move(fixed), threads),
      K_(std::move(K)) {
  if (precision == StepPrecision::kSingle)
    single_blocks_.emplace(*K_, threads_);
  else
    double_blocks_.emplace(*K_, threads_);
  product_scratch_.assign(static_cast<std::size_t>(mass_.size()), NodeSum{});
}

void CsrOperator::set_threads(unsigned threads) {
  threads_ = threads < 1 ? 1 : threads;
  if (single_blocks_) single_blocks_->set_parts(threads_);
  if (double_blocks_) double_blocks_->set_parts(threads_);
}

void CsrOperator::set_block_kernel(BlockKernel kernel) {
  if (single_blocks_) single_blocks_->set_kernel(kernel);
  if (double_blocks_) double_blocks_->set_kernel(kernel);
}

void CsrOperator::for_each_step_block(const BlockVisit& visit) const {
  if (double_blocks_) return double_blocks_->for_each_block(visit);
  single_blocks_->for_each_block([&](std::int32_t i, std::int32_t j, const float* b) {
    const double block[9] = {b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7], b[8]};
    visit(i, j, block);
  });
}

std::size_t CsrOperator::bytes() const {
  const std::lock_guard<std::mutex> lock(K_mutex_);
  return (K_ ? K_->bytes() : 0) +
         (single_blocks_ ? single_blocks_->bytes() : double_blocks_->bytes()) +
         product_scratch_.size() * sizeof(NodeSum) + node_bytes();
}

const CsrMatrix& CsrOperator::stiffness() const {
  const std::lock_guard<std::mutex> lock(K_mutex_);
  if (!K_) K_.emplace(assemble_());
  return *K_;
}

void CsrOperator::set_stiffness_source(std::function<CsrMatrix()> assemble) {
  const std::lock_guard<std::mutex> lock(K_mutex_);
  assemble_ = std::move(assemble);
}

void CsrOperator::release_stiffness() const {
  const std::lock_guard<std::mutex> lock(K_mutex_);
  if (assemble_) K_.reset();
}

CsrMatrix CsrOperator::take_stiffness() const {
  const std::lock_guard<std::mutex> lock(K_mutex_);
  if (!assemble_) return *K_;
  if (!K_) return assemble_();
  CsrMatrix K = std::move(*K_);
  K_.reset();
  return K;
}

bool CsrOperator::holds_stiffness() const {
  const std::lock_guard<std::mutex> lock(K_mutex_);
  return K_.has_value();
}

void CsrOperator::times(const Eigen::VectorXd& x, Eigen::VectorXd& y, bool with_springs,
                        bool stepped) const {
  const std::int64_t n = mass_.size();
  y.resize(x.size());
  const auto finish = [&](std::int64_t i, const double* product) {
    double* out = y.data() + 3 * i;
    if (fixed_[i]) {
      out[0] = out[1] = out[2] = 0.0;
      return;
    }
    std::copy_n(product, 3, out);
    const std::int32_t b = boundary_of_[i];
    if (with_springs && b >= 0) {
      const BoundaryNode& node = boundary_[b];
      node.apply_spring(x.data() + 3 * i, out);
    }
  };
  if (stepped) {
#pragma omp parallel num_threads(threads_)
    fused_product(x.data(), finish);
    return;
  }
  const CsrMatrix& K = stiffness();
#pragma omp parallel for num_threads(threads_) schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    double product[3];
    K.node_rows_dot(static_cast<std::int32_t>(i), x.data(), product);
    finish(i, product);
  }
}

void CsrOperator::stepped_product(const double* x, NodeProducts& take) const {
  // (the blocks hand a thread its nodes in ascending runs, one per part it owns)
  ProductRuns runs(take);
  fused_product(x, [&](std::int64_t i, const double* product) { runs.add(i, product); });
  runs.flush();
}

}  // namespace rumble::fem
