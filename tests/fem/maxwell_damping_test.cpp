// The Maxwell mechanisms (maxwell_damping.hpp): their fit is flat over its band and falls
// outside it, E is the modulus at the band's centre, and in the explicit step the stable step is
// the unrelaxed stiffness's (stable just below it, unstable above), with local time stepping
// too, where Rayleigh's lagged a1 K would limit it. Their time-domain response against the
// frequency domain is checked through the plugin (plugin_test.cpp), their energy in
// energy_balance_test.cpp.
#include "maxwell_damping.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "fem_settings.hpp"
#include "mesh/kuhn_box.hpp"
#include "operator/elasticity.hpp"
#include "random_state.hpp"
#include "settings_from_params.hpp"
#include "time/explicit_solver.hpp"

namespace rumble::fem {
namespace {

double omega(double f_hz) {
  return 2.0 * std::numbers::pi * f_hz;
}

TEST(MaxwellDamping, TheRatioIsFlatOverTheBandAndFallsOutside) {
  // Measured misses of the ratio over the band: 3 mechanisms on 5-100 Hz (1.3 decades) 2.8 %
  // at 2 %, 3.6 % at 5 % (the fit is linearised in the ratio); 4 on 1-200 Hz (2.3 decades)
  // 3.1 %; 2 on 5-100 Hz 15 %. Bounds a little above them. A decade
  // outside the band the ratio is below a fifth of its value (Rayleigh's grows there).
  struct Case {
    double ratio, f_low, f_high;
    int mechanisms;
    double bound;
  };
  for (const Case c : {Case{0.02, 5.0, 100.0, 3, 0.03}, Case{0.05, 5.0, 100.0, 3, 0.04},
                       Case{0.02, 1.0, 200.0, 4, 0.035}, Case{0.02, 5.0, 100.0, 2, 0.16}}) {
    const MaxwellDamping d = MaxwellDamping::fit(c.ratio, c.f_low, c.f_high, c.mechanisms);
    ASSERT_EQ(d.mechanisms(), c.mechanisms);
    EXPECT_TRUE(d.dissipative());
    const double error = d.band_error(c.ratio, c.f_low, c.f_high);
    EXPECT_LT(error, c.bound) << c.mechanisms << " on " << c.f_low << "-" << c.f_high;
    EXPECT_LT(d.ratio_at(omega(c.f_low / 10.0)), 0.3 * c.ratio);
    EXPECT_LT(d.ratio_at(omega(10.0 * c.f_high)), 0.3 * c.ratio);
    // The modulus is the relaxed one at rest and grows with frequency (a causal dispersion).
    EXPECT_NEAR(std::abs(d.modulus(1e-9) - 1.0), 0.0, 1e-9);
    EXPECT_GT(d.modulus(omega(c.f_high)).real(), d.modulus(omega(c.f_low)).real());
    EXPECT_NEAR(d.modulus(1e12).real(), d.unrelaxed(), 1e-6);
    std::printf("[ measured ] %d mechanisms, %g on %g-%g Hz: within %.2f %%, unrelaxed %.4f\n",
                c.mechanisms, c.ratio, c.f_low, c.f_high, 100.0 * error, d.unrelaxed());
  }
  // A narrow band with many mechanisms needs a negative weight: a mechanism that feeds energy
  // in, which the settings refuse (plugin_test.cpp).
  EXPECT_FALSE(MaxwellDamping::fit(0.05, 10.0, 20.0, 3).dissipative());
}

TEST(MaxwellDamping, EIsTheModulusAtTheBandsCentre) {
  // relaxed_modulus_factor scales K so that at sqrt(f_low f_high) the soil is E (1 + 2 i xi'):
  // the real part exactly E, xi' the fit's ratio there.
  DampingRequest r =
      rumble::test::soil_settings(155e6, 0.3, 1800.0, {{"damping", {{"model", "maxwell"}}}})
          .damping;
  const double factor = r.relaxed_modulus_factor();
  const std::complex<double> at_centre =
      factor * r.maxwell_mechanisms().modulus(omega(std::sqrt(r.f_low * r.f_high)));
  EXPECT_NEAR(at_centre.real(), 1.0, 1e-12);
  EXPECT_NEAR(at_centre.imag() / 2.0, r.ratio, 0.03 * r.ratio);
  EXPECT_LT(factor, 1.0);  // the static modulus is below E
  r.maxwell = false;
  EXPECT_EQ(r.relaxed_modulus_factor(), 1.0);
  EXPECT_EQ(r.maxwell_mechanisms().mechanisms(), 0);
}

/// The medium soil (docs/physics.md §1.4) on a Kuhn box of `n` cubes of h [m], free, with the
/// default 2 % over 5-100 Hz by the mechanisms or by Rayleigh's terms.
ExplicitSolver box_solver(int n, double h, bool maxwell) {
  const FemSettings s = rumble::test::soil_settings(
      155e6, 0.3, 1800.0, {{"damping", {{"model", maxwell ? "maxwell" : "rayleigh"}}}});
  const TetMesh m = kuhn_box(n, h);
  ExplicitSolver op(assemble_stiffness(m, s), lumped_mass(m, s), {}, false,
                    std::vector<char>(m.node_count(), 0), s.damping.mass_coefficient(),
                    s.damping.stiffness_coefficient(), 1);
  if (maxwell) op.set_maxwell_damping(s.damping.maxwell_mechanisms());
  return op;
}

TEST(FemMaxwell, StableJustBelowTheUnrelaxedStepAndUnstableAbove) {
  // The stable step is 2 / (omega_max sqrt(1 + sum c_l)) with omega_max of the relaxed K (its
  // 2 % margin: 1 % on the step): the mechanisms' memory follows the new displacement, so the
  // top modes see the unrelaxed stiffness and nothing else limits the step. From a random state
  // (every mode), 3000 steps at 0.97 of it do not grow (they decay: the mechanisms damp every
  // mode); at 1.1 of it the top mode grows (measured: see the output).
  const ExplicitSolver op = box_solver(4, 0.5, true);
  const double below = test::growth_from_random_state(op, 0.97 * op.stable_step(), 3000);
  // (energy_after: the memory, in float, overflows first, and the energy is then not finite)
  const double above = test::energy_after(op, 1.1 * op.stable_step(), 600);
  EXPECT_LT(below, 1.0);
  EXPECT_FALSE(above < 1e6);
  std::printf("[ measured ] energy growth at 0.97 / 1.1 of the step: %.3g / %.3g\n", below, above);
}

TEST(FemMaxwell, TheStepIsLongerThanRayleighsWhereTheMeshIsFine) {
  // Rayleigh's a1 K at the half-step velocity shortens the step as 2 / w (sqrt(1 + xi^2) - xi),
  // xi = a1 w / 2, which grows with the mesh's top frequency w; the mechanisms' stays
  // 1 / sqrt(unrelaxed / relaxed) = 0.963 of the undamped E's. On 0.5 m cubes (w = 2.0e3 rad/s:
  // xi = 0.06, Rayleigh's factor 0.94) the two are close (measured 1.03); on 0.05 m cubes (as a
  // footprint's edge forces; w = 2.0e4: xi = 0.61, factor 0.56) the mechanisms' step is 1.72
  // times Rayleigh's (measured 1.74).
  for (const double h : {0.5, 0.05}) {
    const double ratio =
        box_solver(3, h, true).stable_step() / box_solver(3, h, false).stable_step();
    std::printf("[ measured ] h %g m: Maxwell's step / Rayleigh's %.3f\n", h, ratio);
    if (h < 0.1) {
      EXPECT_GT(ratio, 1.6);
    }
  }
}

TEST(FemMaxwell, LocalStepsTakeALongerStepStably) {
  // Rayleigh's lag rules the local steps out once a1 / dt reaches 0.4 (the stiff soil's meshes);
  // the mechanisms leave the stabilization free. On the box with a stiff corner (c_p 2.45 times
  // the rest, as local_time_stepping_test.cpp) with 3 sub-steps, fitted to a macro step H that
  // one rate takes in 4 sub-steps (as the plugin chooses them): 3 or 2 sub-steps, exactly, and
  // stable for 4000 steps at that step and at 0.8 and 0.6 of it from a random state, where one
  // rate at that step blows up.
  TetMesh m = kuhn_box(6, 0.5);
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const std::int32_t node : m.tets[e]) centre += m.node(node) / 4.0;
    m.layer[e] = (centre.array() < 1.0).all() ? 0 : 1;
  }
  FemSettings s =
      rumble::test::soil_settings(155e6, 0.3, 1800.0, {{"damping", {{"model", "maxwell"}}}});
  s.layers = {{1.0, soils::SoilProperties{930e6, 0.3, 1800.0}}};
  const auto solver = [&] {
    ExplicitSolver op(assemble_stiffness(m, s), lumped_mass(m, s), {}, false,
                      std::vector<char>(m.node_count(), 0), 0.0, 0.0, 1);
    op.set_maxwell_damping(s.damping.maxwell_mechanisms());
    return op;
  };
  ExplicitSolver op = solver();
  const double single = op.single_rate_step(), courant = 0.9, H = 3.996 * courant * single;
  ASSERT_TRUE(op.enable_local_steps(3, H, courant));
  const double count = std::ceil(H / (courant * op.stable_step()) - 1e-9);
  EXPECT_LE(count, 3.0);
  EXPECT_NEAR(courant * op.stable_step() * count, H, 1e-12 * H);
  for (const double ratio : {1.0, 0.8, 0.6}) {
    EXPECT_LT(test::growth_from_random_state(op, ratio * H / count, 4000), 1.0) << ratio;
  }
  EXPECT_FALSE(test::energy_after(solver(), H / count, 100) < 1e6);
  std::printf(
      "[ measured ] local steps with the mechanisms: %g sub-steps per macro step instead "
      "of 4 (step x%.3f)\n",
      count, op.stable_step() / single);
}

}  // namespace
}  // namespace rumble::fem
