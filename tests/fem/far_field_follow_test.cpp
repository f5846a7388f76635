// The static far field's traction as the dynamic step moves it each macro step
// (boundary/static_far_field.hpp, StaticFarField::follow; docs/fem-soil.md §3.2): one pass over
// G gives the new traction and its jump from the last one, against G's dense products; a
// restored state's forces give the jump from them; the bits are the same on any number of
// threads (and so on a rank's rows, which sum each row alike).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <vector>

#include "boundary/absorbing_boundary.hpp"
#include "boundary/static_far_field.hpp"
#include "mesh/kuhn_box.hpp"
#include "settings_from_params.hpp"

namespace rumble::fem {
namespace {

constexpr double kUnheld = 7.0;  // N: what follow() must leave at the nodes it does not hold

/// A 4 m box's far field (its truncation surface's springs) under three sleepers:
/// about 1000 rows, two of the product's blocks of rows.
struct FarFieldBox {
  FemSettings settings = rumble::test::soil_settings(155e6, 0.3, 1800.0);
  TetMesh mesh = kuhn_box(8, 8, 8, 0.5, -2.0, -2.0);
  std::vector<Footprint> sleepers = {
      {-0.6, 0.0, 2.6, 0.26}, {0.0, 0.0, 2.6, 0.26}, {0.6, 0.0, 2.6, 0.26}};
  std::vector<BoundaryNode> boundary =
      absorbing_boundary(mesh, settings, TrackRegion::of(sleepers));

  StaticFarField far() const { return {mesh, settings, sleepers, boundary}; }
  Eigen::VectorXd filled() const {
    return Eigen::VectorXd::Constant(3 * mesh.node_count(), kUnheld);
  }
};

/// What G F puts at each far-field node's DOFs, and the sentinel elsewhere.
Eigen::VectorXd expected(const StaticFarField& far, const Eigen::VectorXd& g, Eigen::VectorXd f) {
  for (std::size_t k = 0; k < far.nodes().size(); ++k)
    f.segment<3>(3 * static_cast<Eigen::Index>(far.nodes()[k])) =
        g.segment<3>(3 * static_cast<Eigen::Index>(k));
  return f;
}

TEST(FarFieldFollow, GivesTheNewTractionAndItsJumpFromTheLastOne) {
  const FarFieldBox box;
  StaticFarField far = box.far();
  ASSERT_GT(far.loads().rows(), 512);  // (the product's blocks of rows: 512)
  const Eigen::Vector3d before(1.2e4, -3.0e3, 5.5e3), now(-2.0e3, 8.0e3, 1.0e4);  // N
  Eigen::VectorXd f = box.filled(), jump = box.filled();
  far.follow(before.data(), now.data(), f, jump, 2);
  const Eigen::VectorXd g_now = far.loads() * now, g_before = far.loads() * before;
  const double scale = g_now.cwiseAbs().maxCoeff() + g_before.cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.0);
  EXPECT_LT((f - expected(far, g_now, box.filled())).cwiseAbs().maxCoeff(), 1e-14 * scale);
  EXPECT_LT((jump - expected(far, g_now - g_before, box.filled())).cwiseAbs().maxCoeff(),
            1e-14 * scale);
}

TEST(FarFieldFollow, TheNextStepsJumpStartsFromTheLastTractionOrARestoredOne) {
  const FarFieldBox box;
  const Eigen::Vector3d a(1e4, 2e4, 3e4), b(-1e4, 4e3, 2e4), c(5e3, -6e3, 7e3),
      restored(2e3, 2e3, -9e3);  // N
  StaticFarField stepped = box.far();
  Eigen::VectorXd f = box.filled(), jump = box.filled();
  stepped.follow(a.data(), b.data(), f, jump, 2);
  // The next macro step: from b, the last call's forces (its product kept, not formed again).
  stepped.follow(b.data(), c.data(), f, jump, 2);
  StaticFarField fresh = box.far();
  Eigen::VectorXd f_fresh = box.filled(), jump_fresh = box.filled();
  fresh.follow(b.data(), c.data(), f_fresh, jump_fresh, 2);
  EXPECT_EQ(f, f_fresh);  // (to the bit)
  EXPECT_EQ(jump, jump_fresh);
  // A state restored to other forces: the jump is from those, not from the last call's.
  stepped.follow(restored.data(), a.data(), f, jump, 2);
  const Eigen::VectorXd g_jump = stepped.loads() * a - stepped.loads() * restored;
  EXPECT_LT((jump - expected(stepped, g_jump, jump)).cwiseAbs().maxCoeff(),
            1e-14 * g_jump.cwiseAbs().maxCoeff());
}

TEST(FarFieldFollow, TheSameBitsOnAnyNumberOfThreads) {
  const FarFieldBox box;
  const Eigen::Vector3d before(3e3, -1e4, 2e4), now(1.5e4, 2.5e3, -4e3);  // N
  std::vector<Eigen::VectorXd> traction, jumps, added;
  for (unsigned threads : {1u, 2u, 3u}) {
    StaticFarField far = box.far();
    Eigen::VectorXd f = box.filled(), jump = box.filled(), sum = box.filled();
    far.follow(before.data(), now.data(), f, jump, threads);
    far.add(now.data(), sum, threads);
    traction.push_back(f);
    jumps.push_back(jump);
    added.push_back(sum);
  }
  for (std::size_t k = 1; k < traction.size(); ++k) {
    EXPECT_EQ(traction[k], traction[0]) << k + 1 << " threads";
    EXPECT_EQ(jumps[k], jumps[0]) << k + 1 << " threads";
    EXPECT_EQ(added[k], added[0]) << k + 1 << " threads";
  }
}

}  // namespace
}  // namespace rumble::fem
