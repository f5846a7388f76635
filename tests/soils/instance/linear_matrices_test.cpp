// The reduced soils give their linear equations M x'' + C x' + K x = B F (u = B^T x) as sparse
// matrices through the boundary (ABI 1.1 linear_matrix), for the monolithic reference and the
// coupling stability analysis. Checked against the soils' own, separately coded, answers: the
// receptance H(f) = B^T (K - w^2 M + i w C)^-1 B must be the plugin's frequency_response, and
// K^-1 B F its static displacement. Tolerance 1e-10 of the largest entry: both are direct
// solves of well-conditioned systems of 9 unknowns (round-off ~1e-15 times a condition number
// below 1e4 here).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include "soil_rig.hpp"

namespace rumble::soiltest {
namespace {

using Eigen::MatrixXd;
using SparseMatrix = Eigen::SparseMatrix<double>;

struct Matrices {
  MatrixXd M, C, K, B;
};

Matrices matrices_of(SoilInstance& soil) {
  Matrices m;
  SparseMatrix s;
  for (auto [which, dense] :
       {std::pair{RUMBLE_MATRIX_MASS, &m.M}, std::pair{RUMBLE_MATRIX_DAMPING, &m.C},
        std::pair{RUMBLE_MATRIX_STIFFNESS, &m.K}, std::pair{RUMBLE_MATRIX_INPUT, &m.B}}) {
    EXPECT_TRUE(soil.linear_matrix(which, s));
    *dense = MatrixXd(s);
  }
  return m;
}

void expect_matrices_give_the_soils_answers(const std::string& type, const nlohmann::json& params) {
  SCOPED_TRACE(type + " " + params.dump());
  const auto layout = sleeper_row(9);
  const Index n = static_cast<Index>(layout.size());
  auto soil = make_soil(type, params, layout);
  const Matrices m = matrices_of(*soil);
  ASSERT_EQ(m.K.rows(), m.B.rows());
  ASSERT_EQ(m.B.cols(), n);
  EXPECT_LT((m.K - m.K.transpose()).norm(), 1e-12 * m.K.norm());
  EXPECT_LT((m.C - m.C.transpose()).norm(), 1e-12 * m.C.norm());
  EXPECT_GE(m.M.minCoeff(), 0.0);

  for (const double f : {0.5, 5.0, 40.0, 120.0}) {
    const double w = 2.0 * 3.141592653589793 * f;
    const Eigen::MatrixXcd D = m.K.cast<std::complex<double>>() -
                               w * w * m.M.cast<std::complex<double>>() +
                               std::complex<double>(0.0, w) * m.C.cast<std::complex<double>>();
    const Eigen::MatrixXcd from_matrices = m.B.transpose().cast<std::complex<double>>() *
                                           D.partialPivLu().solve(m.B.cast<std::complex<double>>());
    const Eigen::MatrixXcd from_soil = receptance(*soil, f, n);
    EXPECT_LT((from_matrices - from_soil).cwiseAbs().maxCoeff(),
              1e-10 * from_soil.cwiseAbs().maxCoeff())
        << "at " << f << " Hz";
  }
  VectorXd F(n);
  for (Index i = 0; i < n; ++i) F[i] = 1e4 * (1.0 + static_cast<double>(i % 3));  // N
  const VectorXd u_matrices = m.B.transpose() * m.K.partialPivLu().solve(m.B * F);
  const VectorXd u_soil = static_displacement(*soil, F);
  EXPECT_LT((u_matrices - u_soil).cwiseAbs().maxCoeff(), 1e-10 * u_soil.cwiseAbs().maxCoeff());
}

TEST(SoilLinearMatrices, WinklerGivenDirectly) {
  expect_matrices_give_the_soils_answers("winkler", {{"k", 1e8}, {"c", 2e5}, {"m", 150.0}});
}

TEST(SoilLinearMatrices, WinklerFromSoilProperties) {
  expect_matrices_give_the_soils_answers("winkler", soil_properties());
}

TEST(SoilLinearMatrices, ClmFromSoilProperties) {
  expect_matrices_give_the_soils_answers("clm", soil_properties());
  expect_matrices_give_the_soils_answers("clm", soil_properties(10e6));
}

TEST(SoilLinearMatrices, DeclaredAsACapability) {
  for (const char* type : {"winkler", "clm"})
    EXPECT_TRUE(soil_type(type).capabilities.has(RUMBLE_CAP_LINEAR_MATRICES)) << type;
}

}  // namespace
}  // namespace rumble::soiltest
