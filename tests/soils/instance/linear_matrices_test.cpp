// The soils give their linear equations M x'' + C x' + K x = B F (u = B^T x) as sparse
// matrices through the boundary (ABI 1.1 linear_matrix), for the monolithic reference and the
// coupling stability analysis. Checked against the soils' own, separately coded, answers: the
// receptance H(f) = B^T (K - w^2 M + i w C)^-1 B must be the plugin's frequency_response, and
// K^-1 B F its static displacement. Tolerance 1e-10 of the largest entry for the reduced soils:
// direct solves of well-conditioned systems of 9 unknowns (round-off ~1e-15 times a condition
// number below 1e4 here). The FEM soil (1215 DOFs; its receptance by UMFPACK, its statics by
// CHOLMOD, here by Eigen's SparseLU): 1e-8, its K spanning more decades (1 on fixed DOFs, 1e9
// N/m on stiff elements).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "soil_rig.hpp"

namespace rumble::soiltest {
namespace {

using Eigen::MatrixXd;
using SparseMatrix = Eigen::SparseMatrix<double>;

struct Matrices {
  SparseMatrix M, C, K, B;
};

Matrices matrices_of(SoilInstance& soil) {
  Matrices m;
  for (auto [which, matrix] :
       {std::pair{RUMBLE_MATRIX_MASS, &m.M}, std::pair{RUMBLE_MATRIX_DAMPING, &m.C},
        std::pair{RUMBLE_MATRIX_STIFFNESS, &m.K}, std::pair{RUMBLE_MATRIX_INPUT, &m.B}})
    EXPECT_TRUE(soil.linear_matrix(which, *matrix));
  return m;
}

/// Largest |entry| of a sparse matrix.
double largest(const SparseMatrix& a) {
  return a.nonZeros() == 0
             ? 0.0
             : Eigen::Map<const Eigen::VectorXd>(a.valuePtr(), a.nonZeros()).cwiseAbs().maxCoeff();
}

/// The matrices' receptance against the soil's to `tolerance`, and their statics K^-1 B F against
/// the soil's to `statics_tolerance` (by default the same; a soil's statics may hold more than
/// its matrices, abi.h linear_matrix).
void expect_matrices_give_the_soils_answers(const std::string& type, const nlohmann::json& params,
                                            double tolerance = 1e-10,
                                            double statics_tolerance = 0.0) {
  if (statics_tolerance == 0.0) statics_tolerance = tolerance;
  SCOPED_TRACE(type + " " + params.dump());
  const auto layout = sleeper_row(9);
  const Index n = static_cast<Index>(layout.size());
  auto soil = make_soil(type, params, layout);
  const Matrices m = matrices_of(*soil);
  ASSERT_EQ(m.K.rows(), m.B.rows());
  ASSERT_EQ(m.B.cols(), n);
  EXPECT_LE(largest(SparseMatrix(m.K - SparseMatrix(m.K.transpose()))), 1e-12 * largest(m.K));
  EXPECT_LE(largest(SparseMatrix(m.C - SparseMatrix(m.C.transpose()))), 1e-12 * largest(m.C));
  for (Index j = 0; j < m.M.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(m.M, j); it; ++it) EXPECT_GE(it.value(), 0.0);

  using ComplexSparse = Eigen::SparseMatrix<std::complex<double>>;
  const ComplexSparse B = m.B.cast<std::complex<double>>();
  for (const double f : {0.5, 5.0, 40.0, 120.0}) {
    const double w = 2.0 * 3.141592653589793 * f;
    const ComplexSparse D = m.K.cast<std::complex<double>>() -
                            w * w * m.M.cast<std::complex<double>>() +
                            std::complex<double>(0.0, w) * m.C.cast<std::complex<double>>();
    Eigen::SparseLU<ComplexSparse> lu(D);
    ASSERT_EQ(lu.info(), Eigen::Success) << "at " << f << " Hz";
    const Eigen::MatrixXcd from_matrices =
        Eigen::MatrixXcd(B.transpose()) * lu.solve(Eigen::MatrixXcd(B));
    const Eigen::MatrixXcd from_soil = receptance(*soil, f, n);
    EXPECT_LT((from_matrices - from_soil).cwiseAbs().maxCoeff(),
              tolerance * from_soil.cwiseAbs().maxCoeff())
        << "at " << f << " Hz";
  }
  VectorXd F(n);
  for (Index i = 0; i < n; ++i) F[i] = 1e4 * (1.0 + static_cast<double>(i % 3));  // N
  Eigen::SparseLU<SparseMatrix> statics(m.K);
  ASSERT_EQ(statics.info(), Eigen::Success);
  const VectorXd u_matrices = m.B.transpose() * statics.solve(VectorXd(m.B * F));
  const VectorXd u_soil = static_displacement(*soil, F);
  EXPECT_LT((u_matrices - u_soil).cwiseAbs().maxCoeff(),
            statics_tolerance * u_soil.cwiseAbs().maxCoeff());
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

TEST(SoilLinearMatrices, FemOnASmallMesh) {
  // A coarse stiff hemisphere (as tests/fem): 405 nodes, its viscous-spring boundary in C and K.
  // Its statics also hold the half-space's far field, which the matrices (the motion about the
  // static state) do not carry: measured 1.3 % of the largest settlement under this uneven
  // load; with Liu's springs alone there is none. In the motion the far field's traction follows
  // the forces unless far_field is "static" (docs/fem-soil.md section 3.2): the matrices are
  // that soil's.
  nlohmann::json params = {{"E", 750e6},
                           {"nu", 0.3},
                           {"rho", 1800.0},
                           {"mesh", {{"radius", 6.0}, {"f_max", 40.0}, {"near_distance", 1.5}}},
                           {"boundary", {{"far_field", "static"}}}};
  expect_matrices_give_the_soils_answers("fem", params, 1e-8, 0.03);
  params["boundary"] = {{"springs", "liu"}};
  expect_matrices_give_the_soils_answers("fem", params, 1e-8);
}

TEST(SoilLinearMatrices, DeclaredAsACapability) {
  for (const char* type : {"winkler", "clm", "fem"})
    EXPECT_TRUE(soil_type(type).capabilities.has(RUMBLE_CAP_LINEAR_MATRICES)) << type;
}

}  // namespace
}  // namespace rumble::soiltest
