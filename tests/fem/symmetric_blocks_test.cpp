// The explicit step's product over K's upper blocks (symmetric_blocks.hpp), both kernels (the
// portable one and, where the processor runs it, the SIMD one: block_kernel_avx2.hpp), against
// the full rows' product in double, for any number of parts and any team size (a team smaller
// than the parts takes several each), with its scratch left zero.
#include "operator/symmetric_blocks.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

#include "mesh/kuhn_box.hpp"
#include "mesh/node_order.hpp"
#include "operator/elasticity.hpp"
#include "settings_from_params.hpp"

namespace rumble::fem {
namespace {

/// K x by the blocks, with `team` threads; checks that every node is handed over once.
template <class Value>
Eigen::VectorXd blocks_times(const SymmetricBlocks<Value>& blocks, const Eigen::VectorXd& x,
                             int team, std::vector<NodeSum>& scratch) {
  Eigen::VectorXd y = Eigen::VectorXd::Constant(x.size(), std::nan(""));
  std::vector<int> handed(static_cast<std::size_t>(blocks.nodes()), 0);
#pragma omp parallel num_threads(team)
  blocks.multiply(x.data(), scratch.data(), [&](std::int64_t i, const double* out) {
    ++handed[static_cast<std::size_t>(i)];
    std::copy_n(out, 3, y.data() + 3 * i);
  });
  EXPECT_TRUE(std::all_of(handed.begin(), handed.end(), [](int n) { return n == 1; }));
  return y;
}

/// A Kuhn box of 5 x 4 x 6 cubes with its nodes moved by up to 0.1 h and numbered at random,
/// two soils: K's blocks all different, each node with anything from 0 to 14 later neighbours,
/// and many blocks across parts.
TetMesh random_mesh() {
  TetMesh m = kuhn_box(5, 4, 6, 0.5);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> shift(-0.05, 0.05);
  for (Eigen::Index i = 0; i < m.node_count(); ++i)
    for (int c = 0; c < 3; ++c) m.nodes(c, i) += shift(random);
  std::vector<std::int32_t> order(static_cast<std::size_t>(m.node_count()));
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), random);
  Eigen::Matrix3Xd moved(3, m.node_count());
  for (std::size_t i = 0; i < order.size(); ++i) moved.col(order[i]) = m.nodes.col(i);
  m.nodes = moved;
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    for (std::int32_t& node : m.tets[e]) node = order[node];
    m.layer[e] = e % 3 == 0 ? 1 : 0;
  }
  for (auto* faces : {&m.ground, &m.truncation})
    for (Triangle& f : *faces)
      for (std::int32_t& node : f) node = order[node];
  return m;
}

/// The reference: K's rows in double, and per DOF the sum of its terms' magnitudes.
struct Reference {
  Eigen::VectorXd product, magnitude;
};
Reference full_rows(const CsrMatrix& K, const Eigen::VectorXd& x) {
  Reference r{Eigen::VectorXd(K.rows()), Eigen::VectorXd::Zero(K.rows())};
  for (std::int64_t row = 0; row < K.rows(); ++row) {
    r.product[row] = K.row_dot(row, x.data());
    for (std::int64_t k = K.row_start()[row]; k < K.row_start()[row + 1]; ++k)
      r.magnitude[row] += std::abs(K.value()[k] * x[K.column()[k]]);
  }
  return r;
}

std::vector<BlockKernel> kernels() {
  std::vector<BlockKernel> k{BlockKernel::kPortable};
  if (block_simd_available()) k.push_back(BlockKernel::kSimd);
  return k;
}

// Double blocks: the same sums as the rows' in another order (fused or not), and K's lower
// triangle replaced by its upper one mirrored (K is symmetric to 1e-12 of its largest entry:
// FemElasticity), so each DOF agrees to 1e-12 of the sum of its terms' magnitudes. Float blocks:
// each entry moves by at most 2^-24 (6e-8) of itself, the sums in double. On any parts and team
// the same numbers to the bit (the order of every sum is fixed by the blocks).
template <class Value>
void check_product(const TetMesh& m, double bound) {
  FemSettings s = rumble::test::soil_settings(155e6, 0.3, 1800.0);
  s.layers = {{1.0, rumble::soils::SoilProperties{387.5e6, 0.25, 1900.0}}};
  const CsrMatrix K = assemble_stiffness(m, s);
  std::srand(3);
  const Eigen::VectorXd x = Eigen::VectorXd::Random(K.rows());
  const Reference ref = full_rows(K, x);
  std::vector<NodeSum> scratch(static_cast<std::size_t>(m.node_count()), NodeSum{});
  for (const auto kernel : kernels()) {
    SymmetricBlocks<Value> blocks(K, 1);
    blocks.set_kernel(kernel);
    const Eigen::VectorXd one = blocks_times(blocks, x, 1, scratch);
    for (Eigen::Index r = 0; r < x.size(); ++r)
      ASSERT_NEAR(one[r], ref.product[r], bound * ref.magnitude[r]) << "DOF " << r;
    for (const unsigned parts : {2u, 3u, 7u}) {
      blocks.set_parts(parts);
      ASSERT_EQ(blocks.parts(), parts);
      for (const int team : {1, 2})
        EXPECT_TRUE(blocks_times(blocks, x, team, scratch) == one) << parts << " parts";
      EXPECT_TRUE(std::all_of(scratch.begin(), scratch.end(), [](const NodeSum& n) {
        return n.v[0] == 0.0 && n.v[1] == 0.0 && n.v[2] == 0.0;
      }));
    }
  }
}

TEST(SymmetricBlocks, ProductIsTheFullRowsProductForAnyPartsAndTeam) {
  check_product<double>(kuhn_box(4, 0.5), 1e-12);
  check_product<float>(kuhn_box(4, 0.5), 1e-7);
}

TEST(SymmetricBlocks, ProductOnARandomMeshIsTheFullRowsProduct) {
  const TetMesh m = random_mesh();
  for (const Tetrahedron& t : m.tets) ASSERT_GT(tet_volume(m, t), 0.0);
  check_product<double>(m, 1e-12);
  check_product<float>(m, 1e-7);
}

// A caller's split (set_part_starts, multiply_parts): parts at given starts, some empty,
// multiplied in two calls (the first parts, then the others, each on the whole team): every
// node handed over once, the same product to the bit as one part's, the scratch left zero.
TEST(SymmetricBlocks, PartsAtGivenStartsMultipliedInTwoCalls) {
  const TetMesh m = random_mesh();
  const CsrMatrix K = assemble_stiffness(m, rumble::test::soil_settings(155e6, 0.3, 1800.0));
  std::srand(11);
  const Eigen::VectorXd x = Eigen::VectorXd::Random(K.rows());
  std::vector<NodeSum> scratch(static_cast<std::size_t>(m.node_count()), NodeSum{});
  for (const auto kernel : kernels()) {
    SymmetricBlocks<float> blocks(K, 1);
    blocks.set_kernel(kernel);
    const Eigen::VectorXd one = blocks_times(blocks, x, 1, scratch);
    const std::int64_t n = blocks.nodes(), shared = n / 5;
    for (const std::vector<std::int64_t>& starts :
         {std::vector<std::int64_t>{0, shared / 2, shared, shared + (n - shared) / 2, n},
          std::vector<std::int64_t>{0, 0, 0, n / 3, n}}) {
      blocks.set_part_starts(starts);
      ASSERT_EQ(blocks.parts(), 4u);
      for (const int team : {1, 2}) {
        Eigen::VectorXd y = Eigen::VectorXd::Constant(x.size(), std::nan(""));
        std::vector<int> handed(static_cast<std::size_t>(n), 0);
        const auto finish = [&](std::int64_t i, const double* out) {
          ++handed[static_cast<std::size_t>(i)];
          std::copy_n(out, 3, y.data() + 3 * i);
        };
#pragma omp parallel num_threads(team)
        {
          blocks.multiply_parts(0, 2, x.data(), scratch.data(), finish);
#pragma omp barrier
          blocks.multiply_parts(2, 4, x.data(), scratch.data(), finish);
        }
        EXPECT_TRUE(std::all_of(handed.begin(), handed.end(), [](int k) { return k == 1; }));
        EXPECT_TRUE(y == one) << "team " << team << ", parts from " << starts[1];
      }
      EXPECT_TRUE(std::all_of(scratch.begin(), scratch.end(), [](const NodeSum& s) {
        return s.v[0] == 0.0 && s.v[1] == 0.0 && s.v[2] == 0.0;
      }));
    }
  }
}

TEST(SymmetricBlocks, RefusesPartStartsThatDoNotCoverTheNodes) {
  const TetMesh m = kuhn_box(2, 0.5);
  const CsrMatrix K = assemble_stiffness(m, rumble::test::soil_settings(155e6, 0.3, 1800.0));
  SymmetricBlocks<double> blocks(K, 1);
  const std::int64_t n = blocks.nodes();
  EXPECT_THROW(blocks.set_part_starts({0, n - 1}), std::invalid_argument);
  EXPECT_THROW(blocks.set_part_starts({1, n}), std::invalid_argument);
  EXPECT_THROW(blocks.set_part_starts({0, 5, 3, n}), std::invalid_argument);
  EXPECT_THROW(blocks.set_part_starts({0}), std::invalid_argument);
  blocks.set_part_starts({0, 3, 3, n});
  EXPECT_EQ(blocks.parts(), 3u);
}

// The nodes taken in a given order (the ranks' parts in one process's order,
// distributed/distributed_operator.hpp): the product, by place in the order, is the one of the
// mesh renumbered in that order (K assembled again: the same entries) to the bit, on any parts.
TEST(SymmetricBlocks, NodesInAGivenOrderSumAsTheRenumberedMesh) {
  const TetMesh m = random_mesh();
  const FemSettings soil = rumble::test::soil_settings(155e6, 0.3, 1800.0);
  const CsrMatrix K = assemble_stiffness(m, soil);
  std::vector<std::int32_t> order(static_cast<std::size_t>(m.node_count()));  // place -> node
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(5));
  TetMesh renumbered = m;
  renumber_nodes(renumbered, order);
  const CsrMatrix K_renumbered = assemble_stiffness(renumbered, soil);
  std::srand(13);
  const Eigen::VectorXd x = Eigen::VectorXd::Random(K.rows());
  std::vector<NodeSum> scratch(static_cast<std::size_t>(m.node_count()), NodeSum{});
  for (const auto kernel : kernels())
    for (const unsigned parts : {1u, 3u}) {
      SymmetricBlocks<float> ordered(K, parts, order), reference(K_renumbered, parts);
      ordered.set_kernel(kernel);
      reference.set_kernel(kernel);
      EXPECT_TRUE(blocks_times(ordered, x, 2, scratch) == blocks_times(reference, x, 2, scratch))
          << parts << " parts";
    }
  EXPECT_THROW(SymmetricBlocks<float>(K, 1, std::vector<std::int32_t>(order.size() - 1, 0)),
               std::invalid_argument);
  order[1] = order[0];
  EXPECT_THROW(SymmetricBlocks<float>(K, 1, order), std::invalid_argument);
}

// The SIMD kernel (fused multiply-adds, another order) against the portable one: the same
// product to 1e-15 of each DOF's terms' magnitudes (a few roundings of 1.1e-16).
TEST(SymmetricBlocks, KernelsAgreeToRounding) {
  if (!block_simd_available()) GTEST_SKIP() << "no AVX2 and FMA here";
  const TetMesh m = random_mesh();
  const CsrMatrix K = assemble_stiffness(m, rumble::test::soil_settings(155e6, 0.3, 1800.0));
  std::srand(5);
  const Eigen::VectorXd x = Eigen::VectorXd::Random(K.rows());
  const Reference ref = full_rows(K, x);
  std::vector<NodeSum> scratch(static_cast<std::size_t>(m.node_count()), NodeSum{});
  SymmetricBlocks<float> simd(K, 2), portable(K, 2);
  portable.set_kernel(BlockKernel::kPortable);
  ASSERT_EQ(simd.kernel(), BlockKernel::kSimd);
  const Eigen::VectorXd a = blocks_times(simd, x, 2, scratch);
  const Eigen::VectorXd b = blocks_times(portable, x, 2, scratch);
  for (Eigen::Index r = 0; r < x.size(); ++r)
    EXPECT_NEAR(a[r], b[r], 1e-15 * ref.magnitude[r]) << "DOF " << r;
}

// Half of K's off-diagonal blocks, all of its diagonal ones: the bytes the step streams.
TEST(SymmetricBlocks, HoldsTheUpperHalfOfTheBlocks) {
  const TetMesh m = kuhn_box(4, 0.5);
  FemSettings s = rumble::test::soil_settings(155e6, 0.3, 1800.0);
  const CsrMatrix K = assemble_stiffness(m, s);
  const SymmetricBlocks<float> blocks(K, 2);
  const std::int64_t nodes = m.node_count(), blocks_of_K = K.nonzeros() / 9;
  const std::size_t values = 9 * static_cast<std::size_t>((blocks_of_K - nodes) / 2 + nodes);
  EXPECT_GE(blocks.bytes(), values * sizeof(float));
  // (and the look-ahead's zeros after the last block, block_view.hpp, and the parts' lists)
  const std::size_t padding = 9 * sizeof(float) * kFarPrefetchAhead + 4 * kPrefetchAhead;
  EXPECT_LT(blocks.bytes(), values * sizeof(float) + 24 * static_cast<std::size_t>(nodes) +
                                (values / 9) * 4 + padding + 1024);
}

}  // namespace
}  // namespace rumble::fem
