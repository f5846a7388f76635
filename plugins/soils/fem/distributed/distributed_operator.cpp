#include "distributed/distributed_operator.hpp"

#include <omp.h>

#include <algorithm>
#include <utility>

#include "distributed/rank_sum.hpp"

namespace rumble::fem {

namespace {

// Node i's three rows times x from its rows' values in K's layout (csr_matrix.hpp: row 3 i + c
// holds 3 x deg(i) values), read as Value and summed in double: CsrMatrix::node_rows_dot's
// loop for K rounded to float.
template <class Value>
void node_rows(const Value* r0, std::int64_t degree, const std::int32_t* node, const double* x,
               double out[3]) {
  const Value* r1 = r0 + 3 * degree;
  const Value* r2 = r1 + 3 * degree;
  double s0 = 0.0, s1 = 0.0, s2 = 0.0;
  for (std::int64_t p = 0; p < degree; ++p) {
    const double* xj = x + 3 * static_cast<std::int64_t>(node[p]);
    const std::int64_t t = 3 * p;
    s0 += double(r0[t]) * xj[0] + double(r0[t + 1]) * xj[1] + double(r0[t + 2]) * xj[2];
    s1 += double(r1[t]) * xj[0] + double(r1[t + 1]) * xj[1] + double(r1[t + 2]) * xj[2];
    s2 += double(r2[t]) * xj[0] + double(r2[t + 1]) * xj[1] + double(r2[t + 2]) * xj[2];
  }
  out[0] = s0;
  out[1] = s1;
  out[2] = s2;
}

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
      shared_(part.shared),
      halo_(*part.halo),
      global_(part.global),
      owned_(static_cast<std::size_t>(part.nodes()), 0),
      comm_(comm),
      shared_products_(3 * static_cast<std::size_t>(part.shared), 0.0) {
  int rank = 0;
  MPI_Comm_rank(comm_, &rank);
  for (std::int32_t i = 0; i < part.nodes(); ++i) owned_[i] = part.owns(i, rank) ? 1 : 0;
  if (precision == StepPrecision::kSingle)
    single_.assign(K_.value().begin(), K_.value().end());  // (rounded to nearest)
}

std::size_t DistributedOperator::bytes() const {
  return K_.bytes() + single_.size() * 4 + shared_products_.size() * 8 + owned_.size() +
         node_bytes();
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

void DistributedOperator::rows_times(std::int32_t i, const double* x, double out[3],
                                     bool stepped) const {
  if (!stepped || single_.empty()) {
    K_.node_rows_dot(i, x, out);
    return;
  }
  node_rows(single_.data() + K_.row_start()[3 * static_cast<std::int64_t>(i)], K_.degree(i),
            K_.neighbours(i), x, out);
}

void DistributedOperator::stepped_product(const double* x, NodeProducts& take) const {
  const std::int64_t n = nodes();
  double* summed = shared_products_.data();
  std::int64_t lo = 0, hi = 0;
  share(0, shared_, lo, hi);
  for (std::int64_t i = lo; i < hi; ++i)
    rows_times(static_cast<std::int32_t>(i), x, summed + 3 * i, true);
#pragma omp barrier
#pragma omp master
  halo_.sum_to_roots_begin(summed, summed, 3);  // (while every thread computes the interior)
  // The interior's products are whole here: handed over at once, in runs from the stack.
  constexpr std::int64_t kRun = 64;
  double run[3 * kRun];
  share(shared_, n, lo, hi);
  for (std::int64_t first = lo; first < hi; first += kRun) {
    const std::int64_t count = std::min(kRun, hi - first);
    for (std::int64_t k = 0; k < count; ++k)
      rows_times(static_cast<std::int32_t>(first + k), x, run + 3 * k, true);
    take.take(first, count, run);
  }
#pragma omp master
  {
    halo_.sum_to_roots_end(summed, summed, 3);
    halo_.to_leaves(summed, summed, 3);
  }
#pragma omp barrier
  share(0, shared_, lo, hi);
  if (hi > lo) take.take(lo, hi - lo, summed + 3 * lo);
}

void DistributedOperator::times(const Eigen::VectorXd& x, Eigen::VectorXd& y, bool with_springs,
                                bool stepped) const {
  const std::int64_t n = nodes();
  y.resize(x.size());
#pragma omp parallel for num_threads(threads_) schedule(static)
  for (std::int64_t i = 0; i < n; ++i)
    rows_times(static_cast<std::int32_t>(i), x.data(), y.data() + 3 * i, stepped);
  halo_.sum_to_roots(y.data(), y.data(), 3);
  halo_.to_leaves(y.data(), y.data(), 3);
  for (std::int64_t i = 0; i < n; ++i) {
    double* out = y.data() + 3 * i;
    if (fixed_[i]) {
      out[0] = out[1] = out[2] = 0.0;
      continue;
    }
    const std::int32_t b = boundary_of_[i];
    if (with_springs && b >= 0) boundary_[b].apply_spring(x.data() + 3 * i, out);
  }
}

}  // namespace rumble::fem
