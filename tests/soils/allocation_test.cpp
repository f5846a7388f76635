// advance() and motion() allocate nothing: every buffer is sized in accept_layout(). Counted with
// tests/support/allocation_counter (a replaced malloc), in an executable of its own.
#include <gtest/gtest.h>

#include <cstddef>
#include <nlohmann/json.hpp>
#include <vector>

#include "allocation_counter.hpp"
#include "soil_cases.hpp"
#include "soil_harness.hpp"

namespace rumble::test {
namespace {

/// Allocations during `steps` macro steps (quadratic waveform prepared beforehand) and motion.
long allocations_while_stepping(const std::string& type, const nlohmann::json& params) {
  constexpr Eigen::Index n = 31;
  TestSoil soil(type, params.dump());
  soil.accept_layout(sleeper_row(n));
  soil.initialize(VectorXd::Constant(n, 1e5));
  VectorXd coeff = VectorXd::Constant(3 * n, 1e3);
  coeff.head(n).setConstant(1e5);
  const rumble_waveform w{2, static_cast<std::uint64_t>(n), coeff.data()};
  VectorXd u(n), v(n);
  soil.api().advance(soil.self(), 0.0, 1e-3, &w);  // the first step factors K_eff (no alloc)
  long allocations = 0;
  {
    const rumble::testing::AllocationCounter counter;
    for (int k = 1; k < 50; ++k) {
      soil.api().advance(soil.self(), k * 1e-3, 1e-3, &w);
      soil.api().motion(soil.self(), u.data(), v.data(), n);
    }
    allocations = counter.count();
  }
  EXPECT_GT(u.norm(), 0.0);
  return allocations;
}

TEST(SoilAllocation, AdvanceAndMotionAllocateNothing) {
  EXPECT_EQ(allocations_while_stepping("winkler", soil_params(kSoils[1])), 0);
  EXPECT_EQ(allocations_while_stepping("clm", soil_params(kSoils[0])), 0);
  EXPECT_EQ(allocations_while_stepping(
                "clm", {{"m_f", 400.0}, {"k_f", 1e8}, {"c_f", 1e5}, {"k_c", 5e7}, {"c_c", 5e4}}),
            0);
}

TEST(SoilAllocation, TheCounterCounts) {
  // The test above can fail: an allocation in the counted window is seen.
  long allocations = 0;
  std::vector<double>* p = nullptr;
  {
    const rumble::testing::AllocationCounter counter;
    p = new std::vector<double>(100);
    allocations = counter.count();
  }
  delete p;
  EXPECT_GE(allocations, 1);
}

}  // namespace
}  // namespace rumble::test
