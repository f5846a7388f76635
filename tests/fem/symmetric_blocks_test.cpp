// The explicit step's product over K's upper blocks (symmetric_blocks.hpp) against the full
// rows' product, for any number of parts and any team size (a team smaller than the parts takes
// several each), with its scratch left zero.
#include "operator/symmetric_blocks.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "mesh/kuhn_box.hpp"
#include "operator/elasticity.hpp"
#include "settings_from_params.hpp"

namespace rumble::fem {
namespace {

/// K x by the blocks, with `team` threads; checks that every node is handed over once.
template <class Value>
Eigen::VectorXd blocks_times(const SymmetricBlocks<Value>& blocks, const Eigen::VectorXd& x,
                             int team, std::vector<double>& scratch) {
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

// Double blocks: the same sums as the rows' in another order, and K's lower triangle replaced
// by its upper one mirrored (K is symmetric to 1e-12 of its largest entry: FemElasticity), so
// each DOF agrees to 1e-12 of the sum of its terms' magnitudes. Float blocks: each entry moves by
// at most 2^-24 (6e-8) of itself.
TEST(SymmetricBlocks, ProductIsTheFullRowsProductForAnyPartsAndTeam) {
  const TetMesh m = kuhn_box(4, 0.5);
  FemSettings s = rumble::test::soil_settings(155e6, 0.3, 1800.0);
  const CsrMatrix K = assemble_stiffness(m, s);
  const Eigen::VectorXd x = Eigen::VectorXd::Random(K.rows());
  Eigen::VectorXd expected(K.rows()), magnitude = Eigen::VectorXd::Zero(K.rows());
  for (std::int64_t r = 0; r < K.rows(); ++r) {
    expected[r] = K.row_dot(r, x.data());
    for (std::int64_t k = K.row_start()[r]; k < K.row_start()[r + 1]; ++k)
      magnitude[r] += std::abs(K.value()[k] * x[K.column()[k]]);
  }
  std::vector<double> scratch(static_cast<std::size_t>(K.rows()), 0.0);
  for (const unsigned parts : {1u, 2u, 3u, 7u}) {
    SymmetricBlocks<double> twin(K, 1);
    twin.set_parts(parts);
    SymmetricBlocks<float> single(K, parts);
    ASSERT_EQ(twin.parts(), parts);
    for (const int team : {1, 2}) {
      const Eigen::VectorXd y = blocks_times(twin, x, team, scratch);
      const Eigen::VectorXd z = blocks_times(single, x, team, scratch);
      for (Eigen::Index r = 0; r < x.size(); ++r) {
        EXPECT_NEAR(y[r], expected[r], 1e-12 * magnitude[r]) << "parts " << parts << ", DOF " << r;
        EXPECT_NEAR(z[r], expected[r], 1e-7 * magnitude[r]) << "parts " << parts << ", DOF " << r;
      }
      EXPECT_TRUE(std::all_of(scratch.begin(), scratch.end(), [](double v) { return v == 0.0; }));
    }
  }
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
  EXPECT_LT(blocks.bytes(), values * sizeof(float) + 24 * static_cast<std::size_t>(nodes) +
                                (values / 9) * 4 + 4096);
}

}  // namespace
}  // namespace rumble::fem
