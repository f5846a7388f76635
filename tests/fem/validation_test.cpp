// The FEM soil on meshes too large for the default suite (label `validation`, excluded from
// `ctest -LE validation`; run with `ctest --preset dev -L validation`): the footing settlement
// converging under refinement (physics.md §8 case 7).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "soil_harness.hpp"

namespace rumble::test {
namespace {

double footing_settlement(double h_near) {
  const nlohmann::json p = {
      {"E", 155e6},
      {"nu", 0.3},
      {"rho", 1800.0},
      {"mesh", {{"radius", 12.0}, {"h_near", h_near}, {"near_distance", 2.0}}}};
  TestSoil soil("fem", p.dump());
  soil.accept_layout({{0.0, 0.0, 1.0, 1.0}});
  return soil.initialize(VectorXd::Constant(1, 1e5))[0];
}

TEST(FemValidation, FootingSettlementConvergesAsHSquared) {
  const double exact = 0.946 * 1e5 * (1.0 - 0.09) / 155e6;  // physics.md §5.3, B = 1 m
  const double coarse = footing_settlement(0.25), fine = footing_settlement(0.125);
  // Measured: -9.2 % and -2.2 %: the error falls 4.2x for h / 2 (second order), from below.
  EXPECT_LT(std::abs(fine / exact - 1.0), 0.035);
  EXPECT_GT((exact - coarse) / (exact - fine), 3.0);
}

}  // namespace
}  // namespace rumble::test
