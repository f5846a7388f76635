// Checkpoints through SoilInstance (its one checkpoint path): advance, save a slot, advance
// (recording), wander off (another macro step size, another force), restore, advance the same way
// again: the two recordings must be identical to the last bit, and so must a third after
// restoring the same slot once more. Bitwise, not within a tolerance: the state is the whole
// state, and the same arithmetic on the same numbers gives the same numbers.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "soil_rig.hpp"

namespace rumble::soiltest {
namespace {

constexpr Index kRestoreN = 7;
constexpr double kH = 1e-3;  // s

struct RestoreModel {
  const char* type;
  nlohmann::json params;
};

/// A smooth, footprint-dependent force history [N] (a passing axle, roughly).
VectorXd force(double t) {
  VectorXd F(kRestoreN);
  for (Index i = 0; i < kRestoreN; ++i)
    F[i] = 5e4 * (1.0 + std::sin(40.0 * t - 0.7 * static_cast<double>(i)));
  return F;
}

/// u and v of every footprint after each of `steps` macro steps from step `first`.
std::vector<double> record(SoilInstance& soil, long first, long steps) {
  std::vector<double> out;
  for (long s = first; s < first + steps; ++s) {
    const double t = static_cast<double>(s) * kH;
    advance_linear(soil, t, kH, force(t), force(t + kH));
    const Motion m = motion(soil, kRestoreN);
    out.insert(out.end(), m.u.data(), m.u.data() + kRestoreN);
    out.insert(out.end(), m.v.data(), m.v.data() + kRestoreN);
  }
  return out;
}

TEST(SoilSaveRestore, RoundTripIsExact) {
  const RestoreModel models[] = {
      {"winkler", {{"k", 2.22e8}, {"c", 3.42e5}, {"m", 500.0}}},
      {"winkler", soil_properties(155e6, 0.4)},  // Wolf's trapped mass
      {"clm", soil_properties()},                // massless
      {"clm", {{"m_f", 300.0}, {"k_f", 9.6e7}, {"c_f", 1.5e5}, {"k_c", 1.04e8}, {"c_c", 1.6e5}}}};
  for (const RestoreModel& m : models) {
    auto soil = make_soil(m.type, m.params, sleeper_row(kRestoreN));
    static_displacement(*soil, force(0.0));
    record(*soil, 0, 40);
    ASSERT_TRUE(soil->can_checkpoint()) << m.params.dump();
    soil->checkpoint_save(0);
    const VectorXd u_saved = motion(*soil, kRestoreN).u;
    const std::vector<double> first = record(*soil, 40, 30);

    // Wander off: another step size (another factorization inside), another force.
    for (int s = 0; s < 5; ++s) {
      advance_held(*soil, 0.07 + 2.5e-3 * s, 2.5e-3, 3.0 * force(0.01 * s));
    }
    ASSERT_NE(motion(*soil, kRestoreN).u, u_saved);

    soil->checkpoint_restore(0);
    EXPECT_EQ(motion(*soil, kRestoreN).u, u_saved);
    const std::vector<double> second = record(*soil, 40, 30);
    EXPECT_EQ(second, first) << m.type << " " << m.params.dump();
    soil->checkpoint_restore(0);  // a slot restores as often as asked
    EXPECT_EQ(record(*soil, 40, 30), first) << m.type << " " << m.params.dump();
    soil->checkpoint_free(0);
  }
}

}  // namespace
}  // namespace rumble::soiltest
