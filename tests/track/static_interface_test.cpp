// The track/soil static interface iteration (engine/track/include/track/static_interface.hpp) on
// maps with a known fixed point, and the half-space footprint flexibility it takes as its prior
// (footprint_flexibility.hpp) against closed forms and fine quadrature.
#include "track/static_interface.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "track/footprint_flexibility.hpp"

namespace rumble {
namespace {

constexpr std::size_t kSleepers = 12;

std::vector<rumble_footprint> sleepers(std::size_t n) {
  std::vector<rumble_footprint> f(n);
  for (std::size_t i = 0; i < n; ++i) f[i] = {0.6 * static_cast<double>(i), 0.0, 2.6, 0.26};
  return f;
}

Eigen::VectorXd as_vector(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

/// A linear track: force = t0 - K u [N], K [N/m] a rail on ballast springs (2e8 N/m per
/// footprint, coupled to the neighbours by -0.5e8 N/m), loaded under the middle sleepers.
struct LinearTrack {
  Eigen::MatrixXd stiffness;
  Eigen::VectorXd load;
  explicit LinearTrack(Eigen::Index n) : stiffness(Eigen::MatrixXd::Zero(n, n)), load(n) {
    for (Eigen::Index i = 0; i < n; ++i) {
      stiffness(i, i) = 2e8;
      if (i > 0) stiffness(i, i - 1) = stiffness(i - 1, i) = -0.5e8;
      load[i] = 5e4 * std::exp(-0.5 * std::pow((static_cast<double>(i) - 0.5 * n) / 2.0, 2));
    }
  }
  InterfaceMap map() const {
    return [this](const std::vector<double>& u, std::vector<double>& f) {
      const Eigen::VectorXd r = load - stiffness * as_vector(u);
      f.assign(r.data(), r.data() + r.size());
    };
  }
  /// The fixed point u = S (t0 - K u) of a linear soil S [m/N], by a dense solve.
  Eigen::VectorXd fixed_point(const Eigen::MatrixXd& flexibility) const {
    const Eigen::Index n = load.size();
    return (Eigen::MatrixXd::Identity(n, n) + flexibility * stiffness)
        .partialPivLu()
        .solve(flexibility * load);
  }
};

InterfaceMap linear_soil(const Eigen::MatrixXd& flexibility, int* solves = nullptr) {
  return [flexibility, solves](const std::vector<double>& f, std::vector<double>& u) {
    if (solves) ++*solves;
    const Eigen::VectorXd r = flexibility * as_vector(f);
    u.assign(r.data(), r.data() + r.size());
  };
}

/// Solves with `flexibility` as the soil; checks the answer against the dense fixed point to
/// the iteration's tolerance (1e-9 of the largest settlement; 1e-8 here for the round-off of the
/// dense reference) and that force is the track's at u. Returns the soil solves.
int solve_and_check(const LinearTrack& track, const Eigen::MatrixXd& flexibility) {
  const auto n = static_cast<std::size_t>(track.load.size());
  std::vector<double> u(n), force(n);
  int counted = 0;
  const InterfaceStatics s =
      solve_interface_statics(track.map(), linear_soil(flexibility, &counted),
                              half_space_flexibility_shape(sleepers(n)), u, force);
  EXPECT_EQ(s.soil_solves, counted);
  const Eigen::VectorXd expected = track.fixed_point(flexibility);
  EXPECT_LE((as_vector(u) - expected).cwiseAbs().maxCoeff(), 1e-8 * expected.cwiseAbs().maxCoeff());
  EXPECT_LE((as_vector(force) - (track.load - track.stiffness * as_vector(u))).norm(), 1e-6);
  return s.soil_solves;
}

// The soil's loop gain here is 2e8 N/m of ballast against 2e7 N/m of soil: the plain iteration
// u <- S(T(u)) diverges by a factor ~10 per step.
constexpr double kSoftFlexibility = 5e-8;  // m/N

// A soil the prior describes exactly (local, or the half-space's shape) is met by the first
// surrogate step: one solve to learn it, one to confirm.
TEST(StaticInterface, ASoilThePriorDescribesIsMetInTwoSolves) {
  const LinearTrack track(kSleepers);
  const Eigen::MatrixXd winkler =
      kSoftFlexibility * Eigen::MatrixXd::Identity(kSleepers, kSleepers);
  EXPECT_EQ(solve_and_check(track, winkler), 2);
  const Eigen::MatrixXd shape = half_space_flexibility_shape(sleepers(kSleepers));
  const Eigen::MatrixXd half_space = kSoftFlexibility / shape(0, 0) * shape;
  EXPECT_EQ(solve_and_check(track, half_space), 2);
}

// Any linear soil, however far from the prior: after n + 1 solves the secants span every force
// direction and the surrogate is the soil, so n + 2 solves at most (round-off aside, which the
// rank filter absorbs). A random symmetric positive definite flexibility of the soft soil's size.
TEST(StaticInterface, AnyLinearSoilIsLearntWithinItsDimension) {
  const LinearTrack track(kSleepers);
  std::srand(7);
  const Eigen::MatrixXd a = Eigen::MatrixXd::Random(kSleepers, kSleepers);
  const Eigen::MatrixXd flexibility =
      kSoftFlexibility / kSleepers *
      (a * a.transpose() + 0.1 * Eigen::MatrixXd::Identity(kSleepers, kSleepers));
  EXPECT_LE(solve_and_check(track, flexibility), static_cast<int>(kSleepers) + 2);
}

// A non-linear track (a cubic hardening of each footprint's ballast, 30 % of the linear force at
// 0.3 mm, so that the chord's Jacobian from rest must be refreshed): the answer is the fixed
// point, checked by applying both maps to it.
TEST(StaticInterface, ANonLinearTrackEndsAtItsFixedPoint) {
  const LinearTrack linear(kSleepers);
  const InterfaceMap track = [&](const std::vector<double>& u, std::vector<double>& f) {
    linear.map()(u, f);
    for (std::size_t i = 0; i < f.size(); ++i) f[i] -= 0.3 * 2e8 * u[i] * (u[i] * u[i] / 9e-8);
  };
  const Eigen::MatrixXd shape = half_space_flexibility_shape(sleepers(kSleepers));
  // A soil near the half-space: its shape plus a local part, which the prior does not fix.
  const Eigen::MatrixXd flexibility =
      kSoftFlexibility *
      (0.7 * shape / shape(0, 0) + 0.3 * Eigen::MatrixXd::Identity(kSleepers, kSleepers));
  std::vector<double> u(kSleepers), force(kSleepers), again(kSleepers), settled(kSleepers);
  const InterfaceStatics s =
      solve_interface_statics(track, linear_soil(flexibility), shape, u, force);
  track(u, again);
  linear_soil(flexibility)(again, settled);
  const double scale = as_vector(u).cwiseAbs().maxCoeff();
  EXPECT_GT(scale, 2e-4);  // the cubic term is at least 13 % of the linear one there
  EXPECT_LE((as_vector(settled) - as_vector(u)).cwiseAbs().maxCoeff(), 1e-8 * scale);
  EXPECT_LE((as_vector(again) - as_vector(force)).norm(), 1e-6);
  EXPECT_LE(s.soil_solves, 6);  // measured 3
}

std::string run_error(const InterfaceMap& soil, int max_solves = 50) {
  const LinearTrack track(kSleepers);
  std::vector<double> u(kSleepers), force(kSleepers);
  InterfaceTolerances tol;
  tol.max_soil_solves = max_solves;
  try {
    solve_interface_statics(track.map(), soil, half_space_flexibility_shape(sleepers(kSleepers)), u,
                            force, tol);
  } catch (const RunError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(StaticInterface, ASoilThatCannotBeMetSaysWhy) {
  const auto nan_soil = [](const std::vector<double>& f, std::vector<double>& u) {
    u.assign(f.size(), std::nan(""));
  };
  EXPECT_NE(run_error(nan_soil).find("the soil returned a non-finite value"), std::string::npos);
  const Eigen::MatrixXd upward =
      -kSoftFlexibility * Eigen::MatrixXd::Identity(kSleepers, kSleepers);
  const std::string upward_error = run_error(linear_soil(upward));
  EXPECT_NE(upward_error.find("the soil settles against its load"), std::string::npos);
  EXPECT_NE(upward_error.find("check the sign of the soil plugin's initialize"), std::string::npos);
  std::srand(7);
  const Eigen::MatrixXd a = Eigen::MatrixXd::Random(kSleepers, kSleepers);
  const Eigen::MatrixXd hard = kSoftFlexibility * (a * a.transpose());
  EXPECT_NE(run_error(linear_soil(hard), 3)
                .find("did not reach a consistent static state in 3 soil solves; this iteration "
                      "needs a linear soil statics"),
            std::string::npos);
}

// The mean of 1/r over a square of side a against itself is 2.9732 / a (closed form); the cell
// sum (2 x 2 cells) is 4.5 % low, which only costs the iteration a little, never its answer.
TEST(FootprintFlexibility, ASquareAgainstItselfIsNearTheClosedForm) {
  const std::vector<rumble_footprint> square{{0.0, 0.0, 1.0, 1.0}};
  const double g = half_space_flexibility_shape(square)(0, 0);
  EXPECT_NEAR(g, 2.97320, 0.05 * 2.97320);
}

/// Mean over footprint a of 1/r to footprint b by the midpoint rule on m x m points each.
double fine_mean_potential(const rumble_footprint& a, const rumble_footprint& b, int m) {
  double sum = 0.0;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k)
        for (int l = 0; l < m; ++l) {
          const double xa = a.x - 0.5 * a.width + (i + 0.5) * a.width / m;
          const double ya = a.y - 0.5 * a.length + (j + 0.5) * a.length / m;
          const double xb = b.x - 0.5 * b.width + (k + 0.5) * b.width / m;
          const double yb = b.y - 0.5 * b.length + (l + 0.5) * b.length / m;
          sum += 1.0 / std::hypot(xa - xb, ya - yb);
        }
  return sum / std::pow(m, 4);
}

// Sleepers 0.6 m apart (the paper's track), 6 m apart (cell sums) and 15 m apart (beyond five
// extents: 1/r between centres): against a 30 x 30-point midpoint rule on each (converged to
// 0.1 %), within 3 %, and symmetric.
TEST(FootprintFlexibility, NeighboursMatchAFineQuadrature) {
  const std::vector<rumble_footprint> f{
      {0.0, 0.0, 2.6, 0.26}, {0.6, 0.0, 2.6, 0.26}, {6.0, 0.0, 2.6, 0.26}, {15.0, 0.0, 2.6, 0.26}};
  const Eigen::MatrixXd g = half_space_flexibility_shape(f);
  EXPECT_EQ((g - g.transpose()).norm(), 0.0);
  for (int j = 1; j < 4; ++j) {
    const double reference = fine_mean_potential(f[0], f[static_cast<std::size_t>(j)], 30);
    EXPECT_NEAR(g(0, j), reference, 0.03 * reference) << "footprint " << j;
  }
}

}  // namespace
}  // namespace rumble
