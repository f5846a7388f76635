#include "statics/mesh_coarsening.hpp"

#include <omp.h>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <algorithm>
#include <atomic>
#include <limits>
#include <stdexcept>
#include <utility>

namespace rumble::fem {

namespace {

/// Gives the heap's free pages back to the system: a chunk's rows of P and A P, freed, leave holes
/// between the coarse rows kept, which would otherwise stay resident (at 1e6 DOFs some 0.2 GB).
void release_free_pages() {
#if defined(__GLIBC__)
  ::malloc_trim(0);
#endif
}

/// Rows formed apart (compressed rows of the rows asked for, in that order).
struct Rows {
  std::vector<std::int64_t> start{0};
  std::vector<int> column;
  std::vector<double> value;
};

/// Gustavson's dense accumulator, as sparse_product's: a column's first product is assigned and
/// the next ones added, in the order given; the row's columns then sorted.
class Accumulator {
 public:
  explicit Accumulator(Eigen::Index columns)
      : sum_(static_cast<std::size_t>(columns)), seen_(static_cast<std::size_t>(columns), -1) {}
  void begin() {
    ++stamp_;
    pattern_.clear();
  }
  void add(int column, double v) {
    const auto c = static_cast<std::size_t>(column);
    if (seen_[c] != stamp_) {
      seen_[c] = stamp_;
      sum_[c] = v;
      pattern_.push_back(column);
    } else {
      sum_[c] += v;
    }
  }
  /// Appends the row's entries, columns ascending.
  void sorted(std::vector<int>& column, std::vector<double>& value) {
    std::sort(pattern_.begin(), pattern_.end());
    for (const int c : pattern_) {
      column.push_back(c);
      value.push_back(sum_[static_cast<std::size_t>(c)]);
    }
  }

 private:
  std::vector<double> sum_;
  std::vector<std::int64_t> seen_;
  std::int64_t stamp_ = -1;
  std::vector<int> pattern_;
};

/// Rows 0 .. count - 1 by row(i, accumulator, column, value), which appends row i's entries; the
/// rows shared out among the threads in contiguous ranges, then put together.
template <class Row>
Rows parallel_rows(std::int64_t count, Eigen::Index columns, unsigned threads, Row&& row) {
  Rows out;
  out.start.assign(static_cast<std::size_t>(count) + 1, 0);
  std::vector<std::vector<int>> column_of(threads);
  std::vector<std::vector<double>> value_of(threads);
  std::vector<std::int64_t> first_of(threads, 0);
#pragma omp parallel num_threads(threads)
  {
    const auto team = static_cast<std::int64_t>(omp_get_num_threads());
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    const std::int64_t first = count * static_cast<std::int64_t>(t) / team;
    const std::int64_t last = count * (static_cast<std::int64_t>(t) + 1) / team;
    first_of[t] = first;
    Accumulator accumulator(columns);
    for (std::int64_t i = first; i < last; ++i) {
      const std::size_t before = column_of[t].size();
      row(i, accumulator, column_of[t], value_of[t]);
      out.start[static_cast<std::size_t>(i) + 1] =
          static_cast<std::int64_t>(column_of[t].size() - before);
    }
  }
  for (std::int64_t i = 0; i < count; ++i) out.start[i + 1] += out.start[i];
  out.column.resize(static_cast<std::size_t>(out.start.back()));
  out.value.resize(out.column.size());
  for (std::size_t t = 0; t < threads; ++t) {
    const auto at = static_cast<std::ptrdiff_t>(out.start[first_of[t]]);
    std::copy(column_of[t].begin(), column_of[t].end(), out.column.begin() + at);
    std::copy(value_of[t].begin(), value_of[t].end(), out.value.begin() + at);
  }
  return out;
}

/// Appends row k of P = P0 - W (A P0) as smoothed aggregation forms it from sparse_product(A,
/// P0): A P0's row scaled by -w_k, then P0's own row added. False where P0's entry has no place
/// in the row (a zero on A's diagonal).
bool prolongator_row(const MeshMatrix& A, const RowSparse& P0, const Eigen::VectorXd& w,
                     std::int64_t k, Accumulator& accumulator, std::vector<int>& column,
                     std::vector<double>& value) {
  accumulator.begin();
  A.for_each_in_row(k, [&](std::int64_t j, double a) {
    for (RowSparse::InnerIterator it(P0, j); it; ++it)
      accumulator.add(static_cast<int>(it.col()), a * it.value());
  });
  const std::size_t first = column.size();
  accumulator.sorted(column, value);
  for (std::size_t e = first; e < column.size(); ++e) value[e] *= -w[k];
  for (RowSparse::InnerIterator it(P0, k); it; ++it) {
    const auto at = std::lower_bound(column.begin() + static_cast<std::ptrdiff_t>(first),
                                     column.end(), static_cast<int>(it.col()));
    if (at == column.end() || *at != it.col()) return false;
    value[static_cast<std::size_t>(at - column.begin())] += it.value();
  }
  return true;
}

/// The given nodes and their neighbours in A's graph, sorted; mark: per node, the last stamp
/// that took it.
std::vector<std::int32_t> with_neighbours(const MeshMatrix& A,
                                          const std::vector<std::int32_t>& nodes,
                                          std::vector<std::int64_t>& mark, std::int64_t stamp) {
  std::vector<std::int32_t> out;
  for (const std::int32_t i : nodes) {
    const std::int32_t* nb = A.neighbours(i);
    for (std::int64_t p = 0; p < A.degree(i); ++p)
      if (mark[static_cast<std::size_t>(nb[p])] != stamp) {
        mark[static_cast<std::size_t>(nb[p])] = stamp;
        out.push_back(nb[p]);
      }
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// What the coarsening shares between its chunks.
struct Coarsening {
  const MeshMatrix& A;
  const RowSparse& P0;
  const Eigen::VectorXd& w;
  Eigen::Index coarse_dofs;
  unsigned threads;
  std::vector<std::int64_t> mark;  // per node (with_neighbours)
  std::vector<std::int32_t> slot;  // per node: its place in the chunk's outer ring, or -1
  std::atomic<bool> zero_diagonal{false};
};

/// Rows of P for the nodes given (3 per node, in their order).
Rows prolongator_rows(Coarsening& c, const std::vector<std::int32_t>& nodes) {
  return parallel_rows(
      3 * static_cast<std::int64_t>(nodes.size()), c.coarse_dofs, c.threads,
      [&](std::int64_t r, Accumulator& acc, std::vector<int>& column, std::vector<double>& value) {
        const std::int64_t k = 3 * static_cast<std::int64_t>(nodes[r / 3]) + r % 3;
        if (!prolongator_row(c.A, c.P0, c.w, k, acc, column, value)) c.zero_diagonal = true;
      });
}

/// Rows of A P for the nodes given, from the rows of P of their neighbours (at c.slot).
Rows product_rows(const Coarsening& c, const std::vector<std::int32_t>& nodes, const Rows& P) {
  return parallel_rows(
      3 * static_cast<std::int64_t>(nodes.size()), c.coarse_dofs, c.threads,
      [&](std::int64_t r, Accumulator& acc, std::vector<int>& column, std::vector<double>& value) {
        acc.begin();
        c.A.for_each_in_row(3 * static_cast<std::int64_t>(nodes[r / 3]) + r % 3,
                            [&](std::int64_t j, double a) {
                              const std::int64_t row = 3 * c.slot[j / 3] + j % 3;
                              for (std::int64_t e = P.start[row]; e < P.start[row + 1]; ++e)
                                acc.add(P.column[e], a * P.value[e]);
                            });
        acc.sorted(column, value);
      });
}

/// The coarse rows [first, last): row I sums P(k, I) (A P)(k, :) over the k of the inner ring
/// (`inner`, whose rows of A P are AP's, in its order) ascending, as R (A P) does.
Rows coarse_rows(const Coarsening& c, const std::vector<std::int32_t>& inner, const Rows& P,
                 const Rows& AP, Eigen::Index first, Eigen::Index last) {
  // R's rows first, restricted to [first, last): (row of A P, P(k, I)) with k ascending.
  Rows R;
  R.start.assign(static_cast<std::size_t>(last - first) + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<std::int64_t> fill(R.start.begin(), R.start.end() - 1);
    for (std::size_t q = 0; q < 3 * inner.size(); ++q) {
      const std::int64_t row = 3 * c.slot[inner[q / 3]] + static_cast<std::int64_t>(q % 3);
      for (std::int64_t e = P.start[row]; e < P.start[row + 1]; ++e) {
        if (P.column[e] < first || P.column[e] >= last) continue;
        const auto I = static_cast<std::size_t>(P.column[e] - first);
        if (pass == 0) {
          ++R.start[I + 1];
        } else {
          R.column[fill[I]] = static_cast<int>(q);
          R.value[fill[I]++] = P.value[e];
        }
      }
    }
    if (pass == 0) {
      for (std::size_t I = 0; I + 1 < R.start.size(); ++I) R.start[I + 1] += R.start[I];
      R.column.resize(static_cast<std::size_t>(R.start.back()));
      R.value.resize(R.column.size());
    }
  }
  return parallel_rows(
      last - first, c.coarse_dofs, c.threads,
      [&](std::int64_t I, Accumulator& acc, std::vector<int>& column, std::vector<double>& value) {
        acc.begin();
        for (std::int64_t e = R.start[I]; e < R.start[I + 1]; ++e)
          for (std::int64_t f = AP.start[R.column[e]]; f < AP.start[R.column[e] + 1]; ++f)
            acc.add(AP.column[f], R.value[e] * AP.value[f]);
        acc.sorted(column, value);
      });
}

/// The coarse rows [first, last) of the aggregates whose nodes are `own`: the rows of P of their
/// two rings of neighbours, of A P of their one ring, and then R (A P).
Rows chunk_rows(Coarsening& c, const std::vector<std::int32_t>& own, Eigen::Index first,
                Eigen::Index last, std::int64_t stamp) {
  const std::vector<std::int32_t> inner = with_neighbours(c.A, own, c.mark, 2 * stamp);
  const std::vector<std::int32_t> outer = with_neighbours(c.A, inner, c.mark, 2 * stamp + 1);
  for (std::size_t q = 0; q < outer.size(); ++q)
    c.slot[static_cast<std::size_t>(outer[q])] = static_cast<std::int32_t>(q);
  const Rows P = prolongator_rows(c, outer);
  const Rows AP = product_rows(c, inner, P);
  Rows rows = coarse_rows(c, inner, P, AP, first, last);
  for (const std::int32_t i : outer) c.slot[static_cast<std::size_t>(i)] = -1;
  return rows;
}

/// P in float, every row formed twice (its length, then its entries), so that it is written
/// once in place.
void float_prolongator(Coarsening& c, RowSparseFloat& P) {
  const std::int64_t n = c.A.rows();
  P.resize(n, c.coarse_dofs);
  int* start = P.outerIndexPtr();
  for (int pass = 0; pass < 2; ++pass) {
#pragma omp parallel num_threads(c.threads)
    {
      Accumulator accumulator(c.coarse_dofs);
      std::vector<int> column;
      std::vector<double> value;
#pragma omp for schedule(dynamic, 256)
      for (std::int64_t r = 0; r < n; ++r) {
        column.clear();
        value.clear();
        if (!prolongator_row(c.A, c.P0, c.w, r, accumulator, column, value)) c.zero_diagonal = true;
        if (pass == 0) {
          start[r + 1] = static_cast<int>(column.size());
          continue;
        }
        std::copy(column.begin(), column.end(), P.innerIndexPtr() + start[r]);
        for (std::size_t e = 0; e < value.size(); ++e)
          P.valuePtr()[start[r] + static_cast<std::ptrdiff_t>(e)] = static_cast<float>(value[e]);
      }
    }
    if (pass == 1) break;
    std::int64_t nonzeros = 0;
    for (std::int64_t r = 0; r < n; ++r) {
      nonzeros += start[r + 1];
      if (nonzeros > std::numeric_limits<int>::max())
        throw std::length_error("multigrid: the prolongator has too many nonzeros for int indices");
      start[r + 1] = static_cast<int>(nonzeros);
    }
    start[0] = 0;
    P.resizeNonZeros(static_cast<Eigen::Index>(nonzeros));
  }
}

/// The chunks' rows one below the other, each freed once copied.
void join(std::vector<Rows>& chunks, Eigen::Index columns, RowSparse& out) {
  std::int64_t nonzeros = 0, rows = 0;
  for (const Rows& chunk : chunks) {
    nonzeros += chunk.start.back();
    rows += static_cast<std::int64_t>(chunk.start.size()) - 1;
  }
  if (nonzeros > std::numeric_limits<int>::max())
    throw std::length_error("multigrid: the coarse matrix has too many nonzeros for int indices");
  out.resize(rows, columns);
  out.resizeNonZeros(static_cast<Eigen::Index>(nonzeros));
  int* start = out.outerIndexPtr();
  std::int64_t row = 0, at = 0;
  for (Rows& chunk : chunks) {
    for (std::size_t r = 0; r + 1 < chunk.start.size(); ++r)
      start[row++] = static_cast<int>(at + chunk.start[r]);
    std::copy(chunk.column.begin(), chunk.column.end(), out.innerIndexPtr() + at);
    std::copy(chunk.value.begin(), chunk.value.end(), out.valuePtr() + at);
    at += chunk.start.back();
    chunk = Rows();
  }
  start[row] = static_cast<int>(at);
}

/// Each aggregate's nodes, ascending: its nodes at [start[a], start[a + 1]).
std::pair<std::vector<std::int64_t>, std::vector<std::int32_t>> aggregate_nodes(
    const MeshAggregates& g) {
  const std::size_t count = g.coarse_start.size() - 1;
  std::vector<std::int64_t> start(count + 1, 0);
  for (const std::int32_t a : g.of_node) ++start[static_cast<std::size_t>(a) + 1];
  for (std::size_t a = 0; a < count; ++a) start[a + 1] += start[a];
  std::vector<std::int32_t> nodes(g.of_node.size());
  std::vector<std::int64_t> fill(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < g.of_node.size(); ++i)
    nodes[static_cast<std::size_t>(fill[static_cast<std::size_t>(g.of_node[i])]++)] =
        static_cast<std::int32_t>(i);
  return {std::move(start), std::move(nodes)};
}

}  // namespace

void coarsen_mesh_matrix(MeshMatrix A, RowSparse& P0, const Eigen::VectorXd& w,
                         const MeshAggregates& aggregates, unsigned threads, RowSparse& coarse,
                         RowSparseFloat& P, std::int64_t chunk_nodes) {
  const auto [start, nodes] = aggregate_nodes(aggregates);
  const auto count = static_cast<std::int64_t>(start.size()) - 1;
  const auto n = static_cast<std::size_t>(A.nodes());
  Coarsening c{A,
               P0,
               w,
               aggregates.coarse_start.back(),
               std::max(1u, threads),
               std::vector<std::int64_t>(n, -1),
               std::vector<std::int32_t>(n, -1)};
  std::vector<Rows> chunks;
  std::vector<std::int32_t> own;
  for (std::int64_t a0 = 0, a1 = 0; a0 < count; a0 = a1) {
    own.clear();
    for (; a1 < count && static_cast<std::int64_t>(own.size()) < chunk_nodes; ++a1)
      own.insert(own.end(), nodes.begin() + start[a1], nodes.begin() + start[a1 + 1]);
    chunks.push_back(chunk_rows(c, own, aggregates.coarse_start[a0], aggregates.coarse_start[a1],
                                static_cast<std::int64_t>(chunks.size())));
    release_free_pages();
  }
  float_prolongator(c, P);
  if (c.zero_diagonal) throw std::logic_error("multigrid: a zero on the stiffness' diagonal");
  {  // A and P0 are done with: freed before the coarse matrix is put together.
    const MeshMatrix freed = std::move(A);
    RowSparse().swap(P0);
  }
  join(chunks, c.coarse_dofs, coarse);
  release_free_pages();
}

}  // namespace rumble::fem
