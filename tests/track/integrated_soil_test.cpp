// The linear soil the monolithic coupler integrates with the track (track/integrated_soil.hpp):
//   - one mass on a spring released from its static deflection follows the average-acceleration
//     rule's closed form: from the first step on (the release makes the start's acceleration
//     inconsistent) u_n = A cos(n theta + phi), theta = 2 atan(omega h / 2), i.e.
//     u_n+1 + u_n-1 = 2 cos(theta) u_n, and the energy 1/2 m v^2 + 1/2 k u^2 stays constant;
//   - statics are K^-1 B F; the step receptance G is B^T (K + c_a M)^-1 B;
//   - a chain numbered in a scrambled order is held in its narrow band (reverse Cuthill-McKee)
//     and moves exactly as the same chain numbered in order;
//   - a soil whose band would not fit is held sparse and moves as the banded one does;
//   - matrices it cannot use are refused with what is wrong.
#include "track/integrated_soil.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>
#include <vector>

#include "core/errors.hpp"

namespace rumble {
namespace {

using Sparse = Eigen::SparseMatrix<double>;

Sparse diagonal(std::initializer_list<double> values) {
  Sparse a(static_cast<Eigen::Index>(values.size()), static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (double v : values) {
    if (v != 0.0) a.insert(i, i) = v;
    ++i;
  }
  a.makeCompressed();
  return a;
}

constexpr double kOscillatorMass = 600.0, kOscillatorStiffness = 6e7;  // kg, N/m: omega = 316 rad/s

TEST(IntegratedSoil, AMassOnASpringFollowsTheAverageAccelerationRuleExactly) {
  IntegratedSoil soil("test", diagonal({kOscillatorMass}), diagonal({0.0}),
                      diagonal({kOscillatorStiffness}), diagonal({1.0}));
  const double force = 5e4, u0 = force / kOscillatorStiffness;  // N, m
  double u = 0.0;
  soil.static_displacement(&force, &u);
  EXPECT_NEAR(u, u0, 1e-15 * u0);
  soil.start_static(&force);
  const Newmark newmark;  // beta 1/4, gamma 1/2
  const double h = 2e-3;  // s: omega h = 0.63, a coarse step where the rule's phase error shows
  soil.factorize(newmark, h);
  EXPECT_NEAR(soil.step_receptance()(0, 0),
              1.0 / (kOscillatorStiffness + newmark.c_a(h) * kOscillatorMass),
              1e-15 / kOscillatorStiffness);
  const double theta = 2.0 * std::atan(std::sqrt(kOscillatorStiffness / kOscillatorMass) * h / 2.0);
  Eigen::VectorXd predicted(1), p(1), zero = Eigen::VectorXd::Zero(1);
  std::vector<double> u_n, energy;
  for (int n = 1; n <= 200; ++n) {
    soil.predict(newmark, h, predicted, p);
    soil.correct(newmark, h, zero);  // released: no force
    const double un = soil.footprint_u(0), vn = soil.footprint_v(0);
    u_n.push_back(un);
    energy.push_back(0.5 * kOscillatorMass * vn * vn + 0.5 * kOscillatorStiffness * un * un);
  }
  // Round-off: ~1e-16 of u0 per step, over 200 steps.
  for (std::size_t n = 1; n + 1 < u_n.size(); ++n)
    ASSERT_NEAR(u_n[n + 1] + u_n[n - 1], 2.0 * std::cos(theta) * u_n[n], 1e-12 * u0) << n;
  for (double e : energy) ASSERT_NEAR(e, energy.front(), 1e-12 * energy.front());
  EXPECT_GT(energy.front(), 0.1 * 0.5 * kOscillatorStiffness * u0 * u0);  // it does oscillate
}

TEST(IntegratedSoil, AStaticStateHeldBeyondTheMatricesShiftsThePositionsNotTheMotion) {
  // The soil's own statics put the footprint 10 % lower than K^-1 B F (a static far field): the
  // footprint starts there, and the motion about it is the matrices' (the same oscillation).
  const auto make = [] {
    return IntegratedSoil("test", diagonal({kOscillatorMass}), diagonal({0.0}),
                          diagonal({kOscillatorStiffness}), diagonal({1.0}));
  };
  IntegratedSoil plain = make(), held = make();
  const double force = 5e4, u0 = force / kOscillatorStiffness, lower = 1.1 * u0;  // N, m, m
  plain.start_static(&force);
  held.start_static(&force, &lower);
  EXPECT_NEAR(held.footprint_u(0), lower, 1e-15 * u0);
  EXPECT_NEAR(held.static_offset(0), 0.1 * u0, 1e-15 * u0);
  const Newmark newmark;
  const double h = 2e-3, released = 0.0;  // s, N
  Eigen::VectorXd predicted(1), p(1), force_now = Eigen::VectorXd::Constant(1, released);
  for (IntegratedSoil* s : {&plain, &held}) s->factorize(newmark, h);
  for (int n = 1; n <= 20; ++n) {
    for (IntegratedSoil* s : {&plain, &held}) {
      s->predict(newmark, h, predicted, p);
      s->correct(newmark, h, force_now);
    }
    ASSERT_NEAR(held.footprint_u(0) - plain.footprint_u(0), 0.1 * u0, 1e-12 * u0) << n;
    ASSERT_EQ(held.footprint_v(0), plain.footprint_v(0)) << n;
  }
}

/// A chain of n masses on springs to the ground and to their neighbours, mass j numbered
/// number[j]; B loads the first and last masses.
struct Chain {
  Sparse M, C, K, B;
};
Chain chain(const std::vector<int>& number) {
  const auto n = static_cast<Eigen::Index>(number.size());
  Chain c{Sparse(n, n), Sparse(n, n), Sparse(n, n), Sparse(n, 2)};
  std::vector<Eigen::Triplet<double>> m, d, k;
  for (Eigen::Index j = 0; j < n; ++j) {
    const int a = number[static_cast<std::size_t>(j)];
    m.emplace_back(a, a, 100.0 + 10.0 * static_cast<double>(j));
    k.emplace_back(a, a, 3e7);
    d.emplace_back(a, a, 2e4);
    if (j + 1 < n) {
      const int b = number[static_cast<std::size_t>(j + 1)];
      for (auto [r, col, v] : {std::tuple{a, a, 1e7}, std::tuple{b, b, 1e7}, std::tuple{a, b, -1e7},
                               std::tuple{b, a, -1e7}})
        k.emplace_back(r, col, v);
    }
  }
  c.M.setFromTriplets(m.begin(), m.end());
  c.C.setFromTriplets(d.begin(), d.end());
  c.K.setFromTriplets(k.begin(), k.end());
  c.B.insert(number.front(), 0) = 1.0;
  c.B.insert(number.back(), 1) = 1.0;
  return c;
}

TEST(IntegratedSoil, AScrambledNumberingIsHeldInItsNarrowBandAndMovesTheSame) {
  const std::vector<int> in_order{0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  const std::vector<int> scrambled{7, 2, 9, 0, 5, 3, 8, 1, 6, 4};  // half bandwidth 9 as given
  const Chain a = chain(in_order), b = chain(scrambled);
  IntegratedSoil ordered("ordered", a.M, a.C, a.K, a.B);
  IntegratedSoil renumbered("scrambled", b.M, b.C, b.K, b.B);
  EXPECT_EQ(ordered.half_bandwidth(), 1u);
  EXPECT_EQ(renumbered.half_bandwidth(), 1u);
  const double force[2] = {5e4, 2e4};  // N
  ordered.start_static(force);
  renumbered.start_static(force);
  const Newmark newmark;
  const double h = 1e-3;  // s
  ordered.factorize(newmark, h);
  renumbered.factorize(newmark, h);
  EXPECT_LT((ordered.step_receptance() - renumbered.step_receptance()).cwiseAbs().maxCoeff(),
            1e-12 * ordered.step_receptance().cwiseAbs().maxCoeff());
  Eigen::VectorXd u0(2), p(2), released = Eigen::VectorXd::Zero(2);
  for (int n = 0; n < 50; ++n) {
    ordered.predict(newmark, h, u0, p);
    ordered.correct(newmark, h, released);
    renumbered.predict(newmark, h, u0, p);
    renumbered.correct(newmark, h, released);
  }
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(renumbered.footprint_u(i), ordered.footprint_u(i), 1e-12 * 5e4 / 3e7) << i;
    EXPECT_NEAR(renumbered.footprint_v(i), ordered.footprint_v(i), 1e-9) << i;
  }
}

// A band too wide for the band storage (a 3D mesh's) is held sparse: the same statics, step
// receptance and motion as the banded storage of the same soil, to round-off.
TEST(IntegratedSoil, ASoilWhoseBandWouldNotFitIsHeldSparseAndMovesTheSame) {
  const Chain c = chain({7, 2, 9, 0, 5, 3, 8, 1, 6, 4});
  IntegratedSoil banded("banded", c.M, c.C, c.K, c.B);
  IntegratedSoil sparse("sparse", c.M, c.C, c.K, c.B, /*max_band_storage=*/1.0);
  EXPECT_FALSE(banded.sparse());
  EXPECT_TRUE(sparse.sparse());
  const double force[2] = {5e4, 2e4};  // N
  double u_banded[2], u_sparse[2];
  banded.static_displacement(force, u_banded);
  sparse.static_displacement(force, u_sparse);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(u_sparse[i], u_banded[i], 1e-12 * 5e4 / 3e7) << i;
  banded.start_static(force);
  sparse.start_static(force);
  const Newmark newmark;
  const double h = 1e-3;  // s
  banded.factorize(newmark, h);
  sparse.factorize(newmark, h);
  EXPECT_LT((sparse.step_receptance() - banded.step_receptance()).cwiseAbs().maxCoeff(),
            1e-12 * banded.step_receptance().cwiseAbs().maxCoeff());
  Eigen::VectorXd u0(2), p(2), released = Eigen::VectorXd::Zero(2);
  for (int n = 0; n < 50; ++n) {
    for (IntegratedSoil* soil : {&banded, &sparse}) {
      soil->predict(newmark, h, u0, p);
      soil->correct(newmark, h, released);
    }
  }
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(sparse.footprint_u(i), banded.footprint_u(i), 1e-12 * 5e4 / 3e7) << i;
    EXPECT_NEAR(sparse.footprint_v(i), banded.footprint_v(i), 1e-9) << i;
  }
}

TEST(IntegratedSoil, MatricesItCannotUseAreRefusedWithWhatIsWrong) {
  Sparse asymmetric(2, 2);
  asymmetric.insert(0, 0) = 1e8;
  asymmetric.insert(1, 1) = 1e8;
  asymmetric.insert(0, 1) = -1e7;  // left uncompressed, as a caller may
  const Sparse zero = diagonal({0.0, 0.0}), input = diagonal({1.0, 1.0});
  const auto refusal = [&](const Sparse& M, const Sparse& K) {
    try {
      IntegratedSoil("clm", M, zero, K, input);
    } catch (const RunError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_THAT(refusal(zero, asymmetric),
              ::testing::HasSubstr("soil 'clm' cannot be integrated with the track (monolithic): "
                                   "K is not symmetric (largest |K - K^T| is 0.1 of its largest "
                                   "entry)"));
  EXPECT_THAT(refusal(diagonal({1.0}), diagonal({1e8, 1e8})),
              ::testing::HasSubstr("M is 1 x 1, K is 2 x 2"));
  EXPECT_THAT(refusal(zero, diagonal({1e8, 0.0})),
              ::testing::HasSubstr("its stiffness K is not positive definite"));
  // Held sparse (a band that would not fit): the same refusal; and a soil too large to factor.
  try {
    IntegratedSoil("fem", zero, zero, diagonal({1e8, 0.0}), input, /*max_band_storage=*/1.0);
    ADD_FAILURE() << "a singular K held sparse was accepted";
  } catch (const RunError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("its stiffness K is not positive definite"));
  }
  const auto n = static_cast<Eigen::Index>(IntegratedSoil::kMaxSparseDofs) + 1;
  Sparse large(n, n), large_input(n, 1);
  large.setIdentity();
  large_input.insert(0, 0) = 1.0;
  try {
    IntegratedSoil("fem", large, large, large, large_input, /*max_band_storage=*/1.0);
    ADD_FAILURE() << "a soil beyond kMaxSparseDofs was accepted";
  } catch (const RunError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("300001 DOFs with a half bandwidth of 0 are too "
                                               "many to factor at every micro-step"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("co-simulation scheme"));
  }
}

}  // namespace
}  // namespace rumble
