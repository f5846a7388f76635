#include "distributed/distributed_operator.hpp"

#include <omp.h>

#include <algorithm>
#include <exception>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "distributed/rank_agreement.hpp"
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

DistributedOperator::DistributedOperator(CsrMatrix K, ElementStiffness elements,
                                         Eigen::VectorXd mass, std::vector<BoundaryNode> boundary,
                                         bool springs, std::vector<char> fixed, unsigned threads,
                                         StepPrecision precision, const MeshPartition& part,
                                         MPI_Comm comm)
    : SoilOperator(std::move(mass), std::move(boundary), springs, std::move(fixed), threads),
      K_(std::move(K)),
      elements_(std::move(elements)),
      scratch_(static_cast<std::size_t>(part.nodes()), NodeSum{}),
      shared_(part.shared),
      part_(part),
      halo_(*part.halo),
      global_(part.global),
      owned_(static_cast<std::size_t>(part.nodes()), 0),
      comm_(comm),
      shared_products_(3 * static_cast<std::size_t>(part.shared), 0.0),
      order_(static_cast<std::size_t>(part.nodes())),
      ordered_x_(3 * static_cast<std::size_t>(part.nodes())) {
  int rank = 0;
  MPI_Comm_rank(comm_, &rank);
  for (std::int32_t i = 0; i < part.nodes(); ++i) owned_[i] = part.owns(i, rank) ? 1 : 0;
  // One process's node order: the shared nodes and the interior each come in it already
  // (mesh_partition.hpp), so this merges the two.
  std::iota(order_.begin(), order_.end(), 0);
  std::stable_sort(order_.begin(), order_.end(),
                   [&part](std::int32_t i, std::int32_t j) { return part.precedes(i, j); });
  if (precision == StepPrecision::kSingle)  // (rounded to nearest)
    single_blocks_.emplace(*K_, threads_, order_);
  else
    double_blocks_.emplace(*K_, threads_, order_);
}

void DistributedOperator::set_threads(unsigned threads) {
  threads_ = threads < 1 ? 1 : threads;
  if (single_blocks_) single_blocks_->set_parts(threads_);
  if (double_blocks_) double_blocks_->set_parts(threads_);
}

const CsrMatrix& DistributedOperator::stiffness() const {
  if (!K_) K_.emplace(assemble_());
  return *K_;
}

std::size_t DistributedOperator::bytes() const {
  return (K_ ? K_->bytes() : 0) + elements_.bytes() + stepped_bytes() +
         scratch_.size() * sizeof(NodeSum) + shared_products_.size() * 8 + owned_.size() +
         order_.size() * 4 + ordered_x_.size() * 8 + node_bytes();
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

void DistributedOperator::for_each_step_block(const BlockVisit& visit) const {
  // (the blocks' nodes are places in one process's order, order_)
  if (double_blocks_)
    return double_blocks_->for_each_block(
        [&](std::int32_t i, std::int32_t j, const double* b) { visit(order_[i], order_[j], b); });
  single_blocks_->for_each_block([&](std::int32_t i, std::int32_t j, const float* b) {
    const double block[9] = {b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7], b[8]};
    visit(order_[i], order_[j], block);
  });
}

double DistributedOperator::sum_over_nodes(const std::vector<double>& per_node) const {
  double mine = 0.0;
  for (std::int64_t i = 0; i < nodes(); ++i)
    if (owned_[i]) mine += per_node[i];
  return sum_in_rank_order(comm_, mine);
}

double DistributedOperator::max_over_nodes(const std::vector<double>& per_node) const {
  double mine = per_node.empty() ? 0.0 : *std::max_element(per_node.begin(), per_node.end());
  double largest = 0.0;  // (a maximum is the same in any order)
  MPI_Allreduce(&mine, &largest, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return largest;
}

void DistributedOperator::gather_x(const double* x) const {
  std::int64_t lo = 0, hi = 0;
  share(0, nodes(), lo, hi);
  for (std::int64_t p = lo; p < hi; ++p)
    std::copy_n(x + 3 * static_cast<std::int64_t>(order_[p]), 3, ordered_x_.data() + 3 * p);
#pragma omp barrier
}

template <class Finish>
void DistributedOperator::blocks_times(const double* x, Finish&& finish) const {
  gather_x(x);
  const std::int32_t* order = order_.data();
  const auto by_node = [order, &finish](std::int64_t p, const double* product) {
    finish(static_cast<std::int64_t>(order[p]), product);
  };
  if (single_blocks_)
    single_blocks_->multiply(ordered_x_.data(), scratch_.data(), by_node);
  else
    double_blocks_->multiply(ordered_x_.data(), scratch_.data(), by_node);
}

void DistributedOperator::stepped_product(const double* x, NodeProducts& take) const {
  double* summed = shared_products_.data();
  const std::int32_t shared = shared_;
  // The interior's products are whole at once: handed over in runs (a thread's interior nodes
  // come in ascending runs: the interior is in one process's order, the blocks' order, between
  // the shared nodes), the shared nodes' kept for their sums over the ranks.
  ProductRuns runs(take);
  blocks_times(x, [&](std::int64_t i, const double* p) {
    if (i < shared)
      std::copy_n(p, 3, summed + 3 * i);
    else
      runs.add(i, p);
  });
  runs.flush();
#pragma omp barrier
#pragma omp master
  try {  // (an exception cannot leave an OpenMP region, nor one rank an exchange alone)
    halo_.sum_to_roots_begin(summed, summed, 3);
    halo_.sum_to_roots_end(summed, summed, 3);
    halo_.to_leaves(summed, summed, 3);
  } catch (const std::exception& e) {
    stop_every_rank(comm_, e.what());
  }
#pragma omp barrier
  std::int64_t lo = 0, hi = 0;
  share(0, shared_, lo, hi);
  if (hi > lo) take.take(lo, hi - lo, summed + 3 * lo);
}

void DistributedOperator::sum_shared_nodes(double* values, int width) const {
  try {  // (an exception cannot leave an OpenMP region, nor one rank an exchange alone)
    halo_.sum_to_roots(values, values, width);
    halo_.to_leaves(values, values, width);
  } catch (const std::exception& e) {
    stop_every_rank(comm_, e.what());
  }
}

void DistributedOperator::times(const Eigen::VectorXd& x, Eigen::VectorXd& y, bool with_springs,
                                bool stepped) const {
  const std::int64_t n = nodes();
  y.resize(x.size());
  double* out = y.data();
  std::exception_ptr failure;  // (this rank's part's: rethrown after the exchanges)
  try {
    if (!failing_.empty()) throw std::runtime_error(failing_);
    if (stepped) {
#pragma omp parallel num_threads(threads_)
      blocks_times(x.data(),
                   [out](std::int64_t i, const double* p) { std::copy_n(p, 3, out + 3 * i); });
    } else if (K_) {
#pragma omp parallel for num_threads(threads_) schedule(static)
      for (std::int64_t i = 0; i < n; ++i)
        K_->node_rows_dot(static_cast<std::int32_t>(i), x.data(), out + 3 * i);
    } else {  // (the rows released: not built again for a product)
      elements_.times(x.data(), out, threads_);
    }
  } catch (...) {
    failure = std::current_exception();
    y.setZero();
  }
  halo_.sum_to_roots(out, out, 3);
  halo_.to_leaves(out, out, 3);
  if (failure) std::rethrow_exception(failure);
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
