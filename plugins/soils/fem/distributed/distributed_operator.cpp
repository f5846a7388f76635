#include "distributed/distributed_operator.hpp"

#include <omp.h>

#include <algorithm>
#include <utility>

#include "distributed/rank_sum.hpp"

namespace rumble::fem {

namespace {

// This thread's share [lo, hi) of the nodes [begin, end) (contiguous, as schedule(static)).
void share(std::int64_t begin, std::int64_t end, std::int64_t& lo, std::int64_t& hi) {
  const std::int64_t team = omp_get_num_threads(), me = omp_get_thread_num();
  lo = begin + (end - begin) * me / team;
  hi = begin + (end - begin) * (me + 1) / team;
}

}  // namespace

DistributedOperator::DistributedOperator(CsrMatrix K, Eigen::VectorXd mass,
                                         std::vector<BoundaryNode> boundary, bool springs,
                                         std::vector<char> fixed, unsigned threads,
                                         StepPrecision precision, const MeshPartition& part,
                                         MPI_Comm comm)
    : SoilOperator(std::move(mass), std::move(boundary), springs, std::move(fixed), threads),
      K_(std::move(K)),
      scratch_(static_cast<std::size_t>(part.nodes()), NodeSum{}),
      shared_(part.shared),
      halo_(*part.halo),
      global_(part.global),
      owned_(static_cast<std::size_t>(part.nodes()), 0),
      comm_(comm),
      shared_products_(3 * static_cast<std::size_t>(part.shared), 0.0) {
  int rank = 0;
  MPI_Comm_rank(comm_, &rank);
  for (std::int32_t i = 0; i < part.nodes(); ++i) owned_[i] = part.owns(i, rank) ? 1 : 0;
  if (precision == StepPrecision::kSingle) {  // (rounded to nearest)
    single_blocks_.emplace(*K_, 1);
    single_blocks_->set_part_starts(part_starts());
  } else {
    double_blocks_.emplace(*K_, 1);
    double_blocks_->set_part_starts(part_starts());
  }
}

std::vector<std::int64_t> DistributedOperator::part_starts() const {
  const std::int64_t n = nodes(), t = threads_;
  std::vector<std::int64_t> starts(static_cast<std::size_t>(2 * t) + 1);
  for (std::int64_t p = 0; p <= t; ++p) {
    starts[p] = shared_ * p / t;
    starts[t + p] = shared_ + (n - shared_) * p / t;
  }
  return starts;
}

void DistributedOperator::set_threads(unsigned threads) {
  threads_ = threads < 1 ? 1 : threads;
  if (single_blocks_) single_blocks_->set_part_starts(part_starts());
  if (double_blocks_) double_blocks_->set_part_starts(part_starts());
}

const CsrMatrix& DistributedOperator::stiffness() const {
  if (!K_) K_.emplace(assemble_());
  return *K_;
}

std::size_t DistributedOperator::bytes() const {
  return (K_ ? K_->bytes() : 0) + stepped_bytes() + scratch_.size() * sizeof(NodeSum) +
         shared_products_.size() * 8 + owned_.size() + node_bytes();
}

double DistributedOperator::dot(const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                                const double* node_weight) const {
  double mine = 0.0;  // (one thread, in node order: the same sum on every run)
  for (std::int64_t i = 0; i < nodes(); ++i) {
    if (!owned_[i]) continue;
    const double w = node_weight ? node_weight[i] : 1.0;
    for (std::int64_t k = 3 * i; k < 3 * i + 3; ++k) mine += w * x[k] * y[k];
  }
  return sum_in_rank_order(comm_, mine);
}

template <class Finish>
void DistributedOperator::blocks_times(unsigned first, unsigned last, const double* x,
                                       Finish&& finish) const {
  if (single_blocks_)
    single_blocks_->multiply_parts(first, last, x, scratch_.data(), finish);
  else
    double_blocks_->multiply_parts(first, last, x, scratch_.data(), finish);
}

void DistributedOperator::stepped_product(const double* x, NodeProducts& take) const {
  const unsigned half = threads_;  // (the shared nodes' parts, then the interior's)
  double* summed = shared_products_.data();
  blocks_times(0, half, x,
               [summed](std::int64_t i, const double* p) { std::copy_n(p, 3, summed + 3 * i); });
#pragma omp barrier
#pragma omp master
  halo_.sum_to_roots_begin(summed, summed, 3);  // (while every thread computes the interior)
  // The interior's products are whole here: handed over at once, in runs from the stack (a
  // thread's nodes come in ascending runs, one per part it owns).
  constexpr std::int64_t kRun = 64;
  double run[3 * kRun];
  std::int64_t first = 0, count = 0;
  blocks_times(half, 2 * half, x, [&](std::int64_t i, const double* p) {
    if (count == kRun || (count > 0 && i != first + count)) {
      take.take(first, count, run);
      count = 0;
    }
    if (count == 0) first = i;
    std::copy_n(p, 3, run + 3 * count);
    ++count;
  });
  if (count > 0) take.take(first, count, run);
#pragma omp master
  {
    halo_.sum_to_roots_end(summed, summed, 3);
    halo_.to_leaves(summed, summed, 3);
  }
#pragma omp barrier
  std::int64_t lo = 0, hi = 0;
  share(0, shared_, lo, hi);
  if (hi > lo) take.take(lo, hi - lo, summed + 3 * lo);
}

void DistributedOperator::times(const Eigen::VectorXd& x, Eigen::VectorXd& y, bool with_springs,
                                bool stepped) const {
  const std::int64_t n = nodes();
  y.resize(x.size());
  double* out = y.data();
  if (stepped) {
    const auto parts = static_cast<unsigned>(2 * threads_);
#pragma omp parallel num_threads(threads_)
    blocks_times(0, parts, x.data(),
                 [out](std::int64_t i, const double* p) { std::copy_n(p, 3, out + 3 * i); });
  } else {
    const CsrMatrix& K = stiffness();
#pragma omp parallel for num_threads(threads_) schedule(static)
    for (std::int64_t i = 0; i < n; ++i)
      K.node_rows_dot(static_cast<std::int32_t>(i), x.data(), out + 3 * i);
  }
  halo_.sum_to_roots(out, out, 3);
  halo_.to_leaves(out, out, 3);
  for (std::int64_t i = 0; i < n; ++i) {
    double* node = out + 3 * i;
    if (fixed_[i]) {
      node[0] = node[1] = node[2] = 0.0;
      continue;
    }
    const std::int32_t b = boundary_of_[i];
    if (with_springs && b >= 0) boundary_[b].apply_spring(x.data() + 3 * i, node);
  }
}

}  // namespace rumble::fem
