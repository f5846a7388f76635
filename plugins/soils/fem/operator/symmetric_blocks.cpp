#include "operator/symmetric_blocks.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "operator/block_kernel_avx2.hpp"

namespace rumble::fem {

template <class Value>
SymmetricBlocks<Value>::SymmetricBlocks(const CsrMatrix& K, unsigned parts)
    : SymmetricBlocks(K, parts, {}) {}

template <class Value>
SymmetricBlocks<Value>::SymmetricBlocks(const CsrMatrix& K, unsigned parts,
                                        const std::vector<std::int32_t>& order) {
  const std::int64_t n = K.rows() / 3;
  if (!order.empty() && static_cast<std::int64_t>(order.size()) != n)
    throw std::invalid_argument("SymmetricBlocks: the order must name each of the " +
                                std::to_string(n) + " nodes once");
  // position[i]: node i's place in the order (its index where no order is given).
  std::vector<std::int32_t> position(static_cast<std::size_t>(n), -1);
  for (std::int64_t p = 0; p < n; ++p) {
    const std::int32_t i = order.empty() ? static_cast<std::int32_t>(p) : order[p];
    if (i < 0 || i >= n || position[i] >= 0)
      throw std::invalid_argument("SymmetricBlocks: the order must name each of the " +
                                  std::to_string(n) + " nodes once");
    position[i] = static_cast<std::int32_t>(p);
  }
  block_start_.assign(static_cast<std::size_t>(n) + 1, 0);
  // Per position: (the later neighbour's position, its place in the node's row), ascending.
  std::vector<std::pair<std::int32_t, std::int64_t>> later;
  const auto later_of = [&](std::int64_t p) {
    const std::int32_t node = order.empty() ? static_cast<std::int32_t>(p) : order[p];
    const std::int32_t* nb = K.neighbours(node);
    later.clear();
    for (std::int64_t q = 0; q < K.degree(node); ++q)
      if (position[nb[q]] >= p) later.emplace_back(position[nb[q]], q);
    std::sort(later.begin(), later.end());
    if (later.empty() || later.front().first != p)
      throw std::invalid_argument("SymmetricBlocks: a node is not its own neighbour");
    return node;
  };
  for (std::int64_t p = 0; p < n; ++p) {
    later_of(p);
    block_start_[p + 1] = block_start_[p] + static_cast<std::int64_t>(later.size());
  }
  // (then kPrefetchAhead zeros, and kFarPrefetchAhead blocks of zeros: the kernels' look-ahead,
  // block_view.hpp)
  column_.assign(static_cast<std::size_t>(block_start_.back() + kPrefetchAhead), 0);
  value_.assign(9 * static_cast<std::size_t>(block_start_.back() + kFarPrefetchAhead), Value{0});
  for (std::int64_t p = 0; p < n; ++p) {
    const std::int32_t node = later_of(p);
    for (std::size_t k = 0; k < later.size(); ++k) {
      const std::int64_t q = block_start_[p] + static_cast<std::int64_t>(k);
      column_[static_cast<std::size_t>(q)] = later[k].first;
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d)
          value_[static_cast<std::size_t>(9 * q + 3 * c + d)] =
              static_cast<Value>(K.block_entry(node, later[k].second, c, d));  // (to nearest)
    }
  }
  set_parts(parts);
  if (block_simd_available()) kernel_ = BlockKernel::kSimd;
}

template <class Value>
void SymmetricBlocks<Value>::set_kernel(BlockKernel kernel) {
  if (kernel == BlockKernel::kSimd && !block_simd_available())
    throw std::invalid_argument(
        "SymmetricBlocks: the SIMD kernel needs AVX2 and FMA, which this processor lacks");
  kernel_ = kernel;
}

template <class Value>
BlockView<Value> SymmetricBlocks<Value>::view(std::int64_t part) const {
  return {part_start_[part],      part_start_[part + 1], cross_start_[part],
          cross_start_[part + 1], block_start_.data(),   column_.data(),
          value_.data(),          cross_from_.data(),    cross_block_.data()};
}

template <class Value>
void SymmetricBlocks<Value>::set_parts(unsigned parts) {
  const std::int64_t n = nodes();
  const std::int64_t count = std::max<std::int64_t>(1, parts);
  std::vector<std::int64_t> starts(static_cast<std::size_t>(count) + 1);
  for (std::int64_t p = 0; p <= count; ++p) starts[p] = n * p / count;
  set_part_starts(starts);
}

template <class Value>
void SymmetricBlocks<Value>::set_part_starts(const std::vector<std::int64_t>& starts) {
  const std::int64_t n = nodes();
  if (starts.size() < 2 || starts.front() != 0 || starts.back() != n ||
      !std::is_sorted(starts.begin(), starts.end()))
    throw std::invalid_argument(
        "SymmetricBlocks: the parts' starts must ascend from node 0 to the node count (" +
        std::to_string(n) + ")");
  // (The plugin sets the threads at every macro step: the lists are rebuilt only on a change.)
  if (starts == part_start_) return;
  part_start_ = starts;
  const auto count = static_cast<std::int64_t>(starts.size()) - 1;
  // The cross blocks, grouped by the part of their column node (the last of equal starts: the
  // part that holds it where some parts are empty).
  const auto part_of = [&](std::int64_t node) {
    return std::upper_bound(part_start_.begin(), part_start_.end(), node) - part_start_.begin() - 1;
  };
  std::vector<std::vector<std::pair<std::int32_t, std::int64_t>>> cross(
      static_cast<std::size_t>(count));  // per part: (k, block)
  for (std::int64_t p = 0; p + 1 < count; ++p)
    for (std::int64_t k = part_start_[p]; k < part_start_[p + 1]; ++k)
      for (std::int64_t q = block_start_[k] + 1; q < block_start_[k + 1]; ++q)
        if (column_[q] >= part_start_[p + 1])
          cross[part_of(column_[q])].emplace_back(static_cast<std::int32_t>(k), q);
  cross_start_.assign(static_cast<std::size_t>(count) + 1, 0);
  cross_from_.clear();
  cross_block_.clear();
  for (std::int64_t p = 0; p < count; ++p) {
    for (const auto& [k, q] : cross[p]) {
      cross_from_.push_back(k);
      cross_block_.push_back(q);
    }
    cross_start_[p + 1] = static_cast<std::int64_t>(cross_block_.size());
  }
}

template <class Value>
std::size_t SymmetricBlocks<Value>::bytes() const {
  return block_start_.size() * 8 + column_.size() * 4 + value_.size() * sizeof(Value) +
         part_start_.size() * 8 + cross_start_.size() * 8 + cross_from_.size() * 4 +
         cross_block_.size() * 8;
}

template <class Value>
void SymmetricBlocks<Value>::gather_cross(const BlockView<Value>& v, const double* x,
                                          NodeSum* scratch) const {
#if RUMBLE_BLOCK_KERNEL_AVX2
  if (kernel_ == BlockKernel::kSimd) return block_kernel_avx2::gather_cross(v, x, scratch);
#endif
  for (std::int64_t c = v.cross_begin; c < v.cross_end; ++c) {
    const Value* b = v.value + 9 * v.cross_block[c];
    const double* xk = x + 3 * static_cast<std::int64_t>(v.cross_from[c]);
    double* sj = scratch[v.column[v.cross_block[c]]].v;
    for (int d = 0; d < 3; ++d)
      sj[d] += double(b[d]) * xk[0] + double(b[3 + d]) * xk[1] + double(b[6 + d]) * xk[2];
  }
}

template <class Value>
void SymmetricBlocks<Value>::sweep(const BlockView<Value>& v, std::int64_t first, std::int64_t last,
                                   const double* x, NodeSum* scratch, double* out) const {
#if RUMBLE_BLOCK_KERNEL_AVX2
  if (kernel_ == BlockKernel::kSimd)
    return block_kernel_avx2::sweep(v, first, last, x, scratch, out);
#endif
  for (std::int64_t i = first; i < last; ++i) {
    const double* xi = x + 3 * i;
    double* si = scratch[i].v;
    const Value* b = v.value + 9 * v.block_start[i];  // the diagonal block
    double o[3];
    for (int c = 0; c < 3; ++c) {
      o[c] = si[c] + double(b[3 * c]) * xi[0] + double(b[3 * c + 1]) * xi[1] +
             double(b[3 * c + 2]) * xi[2];
      si[c] = 0.0;
    }
    for (std::int64_t q = v.block_start[i] + 1; q < v.block_start[i + 1]; ++q) {
      b += 9;
      const std::int64_t j = v.column[q], ahead = v.column[q + kPrefetchAhead];
      __builtin_prefetch(x + 3 * ahead);
      __builtin_prefetch(scratch[ahead].v);
      __builtin_prefetch(b + 9 * kPrefetchAhead);
      const double* xj = x + 3 * j;
      for (int c = 0; c < 3; ++c)
        o[c] +=
            double(b[3 * c]) * xj[0] + double(b[3 * c + 1]) * xj[1] + double(b[3 * c + 2]) * xj[2];
      if (j >= v.end) continue;  // (a later part gathers its own)
      double* sj = scratch[j].v;
      for (int d = 0; d < 3; ++d)
        sj[d] += double(b[d]) * xi[0] + double(b[3 + d]) * xi[1] + double(b[6 + d]) * xi[2];
    }
    std::copy_n(o, 3, out + 4 * (i - first));
  }
}

bool block_simd_available() {
#if RUMBLE_BLOCK_KERNEL_AVX2
  // (GCC's and Clang's checks include the operating system's saving of the AVX registers)
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
  return false;
#endif
}

template class SymmetricBlocks<float>;
template class SymmetricBlocks<double>;

}  // namespace rumble::fem
