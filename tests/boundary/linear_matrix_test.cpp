// The engine checks every CSC matrix a soil hands over (ABI 1.1 linear_matrix) before using it:
// sizes, column pointers, sorted in-range row indices, finite values, and names the defect.
// picky_soil gives M = 0, C = c I, K = k I, B = I, or one of three defects on request. A monolithic
// run also checks that the matrices describe the soil: its own statics against K^-1 B F.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/SparseCore>

#include "boundary_support.hpp"
#include "core/errors.hpp"
#include "plugin/instance.hpp"
#include "plugin/registry.hpp"

namespace rumble::testing {
namespace {

std::unique_ptr<SoilInstance> picky_soil(PluginRegistry& registry, const std::string& defect) {
  registry.load_library(fixture_plugin("boundary_fixtures"));
  const ComponentType* type = registry.find(RUMBLE_KIND_SOIL, "picky_soil");
  EXPECT_NE(type, nullptr);
  auto soil = std::make_unique<SoilInstance>(*type, "/soil",
                                             nlohmann::json{{"k", 1e8},
                                                            {"c", 2e5},
                                                            {"sub_step", 1e-4},
                                                            {"max_step", 1.0},
                                                            {"stall_at", 1e30},
                                                            {"csc_defect", defect}},
                                             ".");
  soil->accept_layout({{0.0, 0.0, 2.6, 0.26}, {0.6, 0.0, 2.6, 0.26}, {1.2, 0.0, 2.6, 0.26}});
  return soil;
}

TEST(LinearMatrix, AValidMatrixArrivesIntact) {
  PluginRegistry registry;
  auto soil = picky_soil(registry, "none");
  Eigen::SparseMatrix<double> K, M;
  ASSERT_TRUE(soil->linear_matrix(RUMBLE_MATRIX_STIFFNESS, K));
  EXPECT_EQ(K.rows(), 3);
  EXPECT_EQ(K.nonZeros(), 3);
  EXPECT_EQ(K.coeff(1, 1), 1e8);
  EXPECT_EQ(K.coeff(0, 1), 0.0);
  ASSERT_TRUE(soil->linear_matrix(RUMBLE_MATRIX_MASS, M));
  EXPECT_EQ(M.nonZeros(), 0);  // massless: an empty matrix of the right size
  EXPECT_EQ(M.cols(), 3);
}

TEST(LinearMatrix, UnsortedRowsAreNamed) {
  PluginRegistry registry;
  auto soil = picky_soil(registry, "unsorted");
  Eigen::SparseMatrix<double> K;
  try {
    soil->linear_matrix(RUMBLE_MATRIX_STIFFNESS, K);
    FAIL() << "accepted";
  } catch (const RunError& e) {
    EXPECT_STREQ(e.what(),
                 "soil 'picky_soil' (/soil): linear_matrix 2 is not a valid CSC matrix: rows not "
                 "sorted (or repeated) in column 1");
  }
}

TEST(LinearMatrix, ANonFiniteValueIsNamed) {
  PluginRegistry registry;
  auto soil = picky_soil(registry, "nan");
  Eigen::SparseMatrix<double> C;
  try {
    soil->linear_matrix(RUMBLE_MATRIX_DAMPING, C);
    FAIL() << "accepted";
  } catch (const RunError& e) {
    EXPECT_STREQ(e.what(),
                 "soil 'picky_soil' (/soil): linear_matrix 1 is not a valid CSC matrix: a value "
                 "is not finite in column 0");
  }
}

TEST(LinearMatrix, MatricesThatDoNotDescribeTheSoilAreRefusedByAMonolithicRun) {
  nlohmann::json s =
      fixture_scenario({{"type", "picky_soil"}, {"params", {{"csc_defect", "stiffer"}}}},
                       {{"type", "monolithic"}, {"params", nlohmann::json::object()}});
  CliResult r;
  run_in("linear_matrix_stiffer", s, r);
  EXPECT_EQ(r.exit_code, 3) << r.output;
  // K twice the soil's: the matrices' settlement is half the plugin's, far beyond the tenth
  // that a static far field may add.
  EXPECT_THAT(r.output, ::testing::HasSubstr("soil 'picky_soil': its statics hold the footprints "
                                             "up to"));
  EXPECT_THAT(r.output, ::testing::HasSubstr("beyond its linear matrices' K^-1 B F"));
  EXPECT_THAT(r.output, ::testing::HasSubstr("cannot be integrated with the track"));
}

}  // namespace
}  // namespace rumble::testing
