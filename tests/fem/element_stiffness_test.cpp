// K x formed element by element without K's rows (plugins/soils/fem/operator/
// element_stiffness.hpp; the ranks' statics use it once the rows are freed) against the
// assembled rows' product: the same operator to rounding, on a layered box with the Maxwell
// mechanisms' relaxed modulus (so the layer table and the modulus' scaling are both checked), on
// one thread and on two, run after run the same to the bit, and again once its copy is freed.
#include "operator/element_stiffness.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cstdlib>

#include "mesh/kuhn_box.hpp"
#include "settings_from_params.hpp"

namespace rumble::fem {
namespace {

// A box of 0.5 m cubes, its tetrahedra above 0.6 m in the layer (index 0), the rest in the
// half-space (index 1, layers.size()).
TetMesh layered_box() {
  TetMesh m = kuhn_box(5, 4, 4, 0.5);
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    double depth = 0.0;
    for (const std::int32_t a : m.tets[e]) depth += 0.25 * m.nodes(2, a);
    m.layer[e] = depth < 0.6 ? 0 : 1;
  }
  return m;
}

FemSettings layered_settings() {
  return rumble::test::soil_settings(
      155e6, 0.3, 1800.0,
      {{"layers", {{{"thickness", 0.6}, {"E", 40e6}, {"nu", 0.45}, {"rho", 1700.0}}}},
       {"damping", {{"model", "maxwell"}}}});
}

TEST(ElementStiffness, IsTheAssembledRowsProductToRounding) {
  const TetMesh m = layered_box();
  const FemSettings s = layered_settings();
  ASSERT_LT(s.damping.relaxed_modulus_factor(), 0.99);  // (the scaling is exercised)
  const CsrMatrix K = assemble_stiffness(m, s);
  const ElementStiffness elements(m, s);
  std::srand(7);
  const Eigen::VectorXd x = Eigen::VectorXd::Random(m.dof_count());
  Eigen::VectorXd rows(m.dof_count()), formed(m.dof_count()), two(m.dof_count());
  K.multiply_rows(x.data(), rows.data(), 0, K.rows());
  elements.times(x.data(), formed.data(), 1);
  const double scale = rows.cwiseAbs().maxCoeff();
  // (sums of about 40 terms of size |K| |x| in another order: 1e-14 of the largest is some 50
  // roundings; a wrong modulus or layer is off by percents)
  EXPECT_LT((formed - rows).cwiseAbs().maxCoeff(), 1e-14 * scale);
  elements.times(x.data(), two.data(), 2);
  EXPECT_LT((two - rows).cwiseAbs().maxCoeff(), 1e-14 * scale);
  Eigen::VectorXd again(m.dof_count());
  elements.times(x.data(), again.data(), 2);
  EXPECT_EQ(again, two);  // (the threads' copies added in one order)
  const std::size_t held = elements.bytes();
  elements.release();  // (the sorted tetrahedra freed, made again at the next product)
  EXPECT_LT(elements.bytes(), held / 10);
  elements.times(x.data(), again.data(), 2);
  EXPECT_EQ(again, two);
  const std::vector<double> rows_diagonal = K.diagonal();
  const Eigen::Map<const Eigen::VectorXd> diagonal(rows_diagonal.data(), m.dof_count());
  EXPECT_LT((elements.diagonal() - diagonal).cwiseAbs().maxCoeff(),
            1e-14 * diagonal.cwiseAbs().maxCoeff());
}

// The element matrices' rows (the ranks' aggregation multigrid sums P_e^T K_e P_e from them) add up
// to the assembled K: their products K_e x_e summed over the tetrahedra are the rows' product.
TEST(ElementStiffness, ElementMatricesSumToTheAssembledRows) {
  const TetMesh m = layered_box();
  const FemSettings s = layered_settings();
  const CsrMatrix K = assemble_stiffness(m, s);
  const ElementStiffness elements(m, s);
  std::srand(11);
  const Eigen::VectorXd x = Eigen::VectorXd::Random(m.dof_count());
  Eigen::VectorXd rows(m.dof_count()), summed = Eigen::VectorXd::Zero(m.dof_count());
  K.multiply_rows(x.data(), rows.data(), 0, K.rows());
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    Eigen::Matrix<double, 12, 12> k;
    for (int a = 0; a < 4; ++a) k.middleRows<3>(3 * a) = elements.element_row(e, a);
    EXPECT_LT((k - k.transpose()).cwiseAbs().maxCoeff(), 1e-12 * k.cwiseAbs().maxCoeff());
    Eigen::Matrix<double, 12, 1> local;
    for (int a = 0; a < 4; ++a) local.segment<3>(3 * a) = x.segment<3>(3 * m.tets[e][a]);
    const Eigen::Matrix<double, 12, 1> y = k * local;
    for (int a = 0; a < 4; ++a) summed.segment<3>(3 * m.tets[e][a]) += y.segment<3>(3 * a);
  }
  EXPECT_LT((summed - rows).cwiseAbs().maxCoeff(), 1e-14 * rows.cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace rumble::fem
