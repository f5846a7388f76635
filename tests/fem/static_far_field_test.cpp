// The static state of the truncated FEM soil against the half-space's (docs/fem-soil.md section
// 3.2): surface receivers under a row of loaded sleepers against Boussinesq's point load
// integrated over each footprint (Love's rectangle), on the 12 m hemisphere that the quick study
// and the tests use, and the footing's settlement converging from below as the mesh is refined.
#include <gtest/gtest.h>
#include <rumble/abi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "boussinesq.hpp"
#include "sanitizer.hpp"
#include "soil_harness.hpp"

namespace rumble::test {
namespace {

constexpr double kMediumE = 155e6, kMediumNu = 0.3;  // the paper's medium soil [Pa, -]

/// Vertical surface displacement [m] at (x, y) under forces[j] [N] spread uniformly over the
/// footprints: (1 - nu^2) / (pi E) q_j times the integral of 1/R over footprint j.
double half_space_settlement(const std::vector<rumble_footprint>& footprints,
                             const VectorXd& forces, double E, double nu, double x, double y) {
  double u = 0.0;
  for (std::size_t j = 0; j < footprints.size(); ++j) {
    const rumble_footprint& f = footprints[j];
    const double a = 0.5 * f.width, b = 0.5 * f.length;
    const double q = forces[static_cast<Eigen::Index>(j)] / (4.0 * a * b);
    u += q * soils::inverse_distance_integral(f.x - a - x, f.x + a - x, f.y - b - y, f.y + b - y);
  }
  return u * (1.0 - nu * nu) / (std::numbers::pi * E);
}

/// Each probe's vertical displacement [m] in the newest of the samples waiting (at most 1024).
std::vector<double> newest_probe_settlements(TestSoil& soil, std::size_t probes) {
  std::vector<double> times(1024), values(times.size() * probes * RUMBLE_PROBE_VALUES);
  std::uint64_t n = 0;
  if (soil.api().probe_samples(soil.self(), times.data(), values.data(), times.size(), &n) !=
          RUMBLE_OK ||
      n == 0)
    throw std::runtime_error("probe_samples");
  std::vector<double> uz(probes);
  for (std::size_t p = 0; p < probes; ++p)
    uz[p] = values[((n - 1) * probes + p) * RUMBLE_PROBE_VALUES + 5];
  return uz;
}

/// The probes' static vertical displacements [m]: the soil is initialized under `forces` and
/// stepped once under the same forces (which moves nothing, plugin_test.cpp), so that the
/// probes record the static state.
std::vector<double> static_probe_settlements(TestSoil& soil, const VectorXd& forces,
                                             const std::vector<rumble_probe>& probes) {
  const double H = 1e-3;
  if (soil.api().set_probes(soil.self(), probes.data(), probes.size(), H) != RUMBLE_OK)
    throw std::runtime_error("set_probes");
  soil.initialize(forces);
  soil.advance_linear(0.0, H, forces, forces);
  return newest_probe_settlements(soil, probes.size());
}

/// The paper's wheel (2 x 50 kN) at rest over sleeper 6 of a 30-sleeper track on the medium soil:
/// the footprint forces at t = 0 of `rumble run scenarios/paper/study/track_on_fem_soil.json`
/// with /track/sleepers/count 30 and /soil/params/mesh/radius 12 [N]. The track's weight is not
/// in them (the run's forces are those the wheel adds), so the load sits 5 m off the centre.
VectorXd wheel_over_sleeper_six() {
  return (VectorXd(30) << -2685.7, -1358.5, 2144.0, 11515.2, 27803.9, 39892.2, 27697.2, 11351.1,
          1968.5, -1213.6, -1396.1, -785.9, -274.3, -31.1, 39.9, 35.9, 16.5, 4.1, -1.8, -2.5, -1.6,
          -0.8, -0.5, -0.4, 0.0, 0.2, 0.6, 1.2, 0.7, -3.3)
      .finished();
}

/// The 30-sleeper track (17.4 m) on the 12 m hemisphere, meshed for 40 Hz near the track (at the
/// quick study's 30 Hz the receiver at 2.5 m abreast of the wheel is 3.6 % off, at 50 Hz 1.1 %:
/// the mesh's own error), with the boundary springs `springs`.
nlohmann::json track_soil(const std::string& springs) {
  return {{"E", kMediumE},
          {"nu", kMediumNu},
          {"rho", 1800.0},
          {"mesh", {{"radius", 12.0}, {"f_max", 40.0}, {"near_distance", 4.0}}},
          {"boundary", {{"springs", springs}}}};
}

/// Surface receivers at 2.5 and 5 m across the track, at its centre and abreast of the wheel.
std::vector<rumble_probe> track_receivers() {
  return {{"centre, 2.5 m", 8.7, 2.5, 0.0},
          {"centre, 5 m", 8.7, 5.0, 0.0},
          {"wheel, 2.5 m", 3.0, 2.5, 0.0},
          {"wheel, 5 m", 3.0, 5.0, 0.0}};
}

/// Each receiver's vertical displacement over the half-space's under `forces`.
std::vector<double> ratios_to_half_space(const std::vector<double>& fem, const VectorXd& forces,
                                         const char* what) {
  const std::vector<rumble_footprint> sleepers = sleeper_row(30);
  const std::vector<rumble_probe> probes = track_receivers();
  std::vector<double> ratios;
  for (std::size_t p = 0; p < probes.size(); ++p) {
    const double exact =
        half_space_settlement(sleepers, forces, kMediumE, kMediumNu, probes[p].x, probes[p].y);
    ratios.push_back(fem[p] / exact);
    std::printf("%s, %s: FEM %.4e m, half-space %.4e m, ratio %.4f\n", what, probes[p].name, fem[p],
                exact, ratios.back());
  }
  return ratios;
}

std::vector<double> static_ratios(const std::string& springs) {
  TestSoil soil("fem", track_soil(springs).dump());
  soil.accept_layout(sleeper_row(30));
  const VectorXd forces = wheel_over_sleeper_six();
  return ratios_to_half_space(static_probe_settlements(soil, forces, track_receivers()), forces,
                              ("static, springs " + springs).c_str());
}

TEST(FemStaticFarField, SurfaceReceiversBesideALoadedTrackSettleAsTheHalfSpace) {
  RUMBLE_SKIP_STUDY_UNDER_ASAN();
  for (double ratio : static_ratios("half_space")) EXPECT_NEAR(ratio, 1.0, 0.03);
  // Liu's springs alone, the former default, hold too little abreast of the wheel (measured
  // 1.10 and 1.13 on the 50 Hz mesh): the check fails on them.
  const std::vector<double> liu = static_ratios("liu");
  EXPECT_GT(*std::max_element(liu.begin(), liu.end()), 1.05);
}

/// Largest |Re H(f) F - u| over the footprints, relative to the largest |u| [-]: the
/// receptance's quasi-static limit against the soil's static footprint settlements u under F.
double receptance_against_statics(const nlohmann::json& params, double f_hz) {
  TestSoil soil("fem", params.dump());
  soil.accept_layout(sleeper_row(30));
  const VectorXd F = wheel_over_sleeper_six();
  const VectorXd u = soil.initialize(F);
  const VectorXd from_receptance = (soil.receptance(f_hz) * F).real();
  return (from_receptance - u).cwiseAbs().maxCoeff() / u.cwiseAbs().maxCoeff();
}

// The receptance takes the far field as the steps do (B + G / (1 + i w tau) on the right-hand
// side), so at a low frequency it gives the soil's static footprint settlements, the
// half-space's; held at the statics' ("static", what the linear matrices describe), it gives
// the springs' softer answer.
TEST(FemStaticFarField, TheReceptancesLowFrequencyLimitIsTheStatics) {
  nlohmann::json params = track_soil("half_space");
  params["mesh"]["f_max"] = 20.0;  // Hz: coarser than the other checks' (two LUs)
  const double follows = receptance_against_statics(params, 0.05);
  params["boundary"]["far_field"] = "static";
  const double held = receptance_against_statics(params, 0.05);
  std::printf(
      "receptance at 0.05 Hz times F against the statics: %.2e (far field follows), "
      "%.2e (static)\n",
      follows, held);
  EXPECT_LT(follows, 2e-3);
  EXPECT_GT(held, 5.0 * follows);
}

TEST(FemStaticFarField, ALoadChangeSettlesAsTheHalfSpace) {
  // From the wheel's load to twice it, held 0.5 s: the far field's traction follows the forces
  // with its lag (about 0.07 s here; docs/fem-soil.md section 3.2), so the change settles as
  // the statics do: measured 1.001 at the centre, 1.015 and 1.005 abreast of the wheel at 2.5
  // and 5 m. When the traction was the statics' alone, the change reached the boundary through
  // the springs, fitted to a uniform pressure, not to this load 5 m off the centre: 1.077 and
  // 1.133 abreast of the wheel (Liu's springs: 1.13, 1.13).
  const VectorXd F0 = wheel_over_sleeper_six(), F1 = 2.0 * F0;
  TestSoil soil("fem", track_soil("half_space").dump());
  soil.accept_layout(sleeper_row(30));
  const std::vector<rumble_probe> probes = track_receivers();
  const double H = 1e-3;
  ASSERT_EQ(soil.api().set_probes(soil.self(), probes.data(), probes.size(), H), RUMBLE_OK);
  soil.initialize(F0);
  for (double t = 0.0; t < 0.5 * kSanitizedShare - 1e-9; t += H) soil.advance_linear(t, H, F1, F1);
  RUMBLE_PHYSICS_IN_THE_DEV_BUILD_ONLY();
  const std::vector<double> ratios =
      ratios_to_half_space(newest_probe_settlements(soil, probes.size()), F1, "after the change");
  for (double ratio : ratios) EXPECT_NEAR(ratio, 1.0, 0.03);
}

/// Mean settlement [m] of a 1 m square footing under 100 kPa; `more` merged into params.mesh.
double square_footing_settlement(double nu, double h_near,
                                 const nlohmann::json& more = nlohmann::json::object()) {
  nlohmann::json params = {
      {"E", kMediumE},
      {"nu", nu},
      {"rho", 1800.0},
      {"mesh", {{"radius", 12.0}, {"h_near", h_near}, {"near_distance", 2.0}}}};
  params["mesh"].merge_patch(more);
  TestSoil soil("fem", params.dump());
  soil.accept_layout({{0.0, 0.0, 1.0, 1.0}});
  return soil.initialize(VectorXd::Constant(1, 1e5))[0];
}

TEST(FemStaticFarField, AFootingsSettlementConvergesFromBelowAtNuPointFour) {
  RUMBLE_SKIP_STUDY_UNDER_ASAN();
  // Mean settlement of a flexible 1 m square under 100 kPa: 0.946 q B (1 - nu^2) / E
  // (docs/soils.md, Love's rectangle). Compatible linear elements are too stiff, so with a
  // boundary that holds the half-space's static field the settlement rises towards the closed
  // form from below; a boundary too soft overshot it at B/8.
  const double nu = 0.4, exact = 0.946 * 1e5 * (1.0 - nu * nu) / kMediumE;
  const double coarse = square_footing_settlement(nu, 0.25) / exact;
  const double fine = square_footing_settlement(nu, 1.0 / 6.0) / exact;
  std::printf("settlement / closed form: %.4f at B/4, %.4f at B/6\n", coarse, fine);
  EXPECT_LT(coarse, fine);
  EXPECT_LT(fine, 1.0);
  EXPECT_GT(fine, 0.9);
}

// mesh.refine (docs/fem-soil.md §2): gmsh meshes at 0.5 m and the plugin refines once, which
// settles as the mesh gmsh makes at 0.25 m does, not as the coarse one.
TEST(FemStaticFarField, AFootingOnACoarseMeshRefinedOnceSettlesAsOnAFineMesh) {
  RUMBLE_SKIP_STUDY_UNDER_ASAN();
  const double nu = 0.4, exact = 0.946 * 1e5 * (1.0 - nu * nu) / kMediumE;
  const nlohmann::json h_max = {{"h_max", 1.5}};  // (refined: gmsh's 3 m, R / 4)
  const double coarse = square_footing_settlement(nu, 0.5, h_max) / exact;
  const double refined =
      square_footing_settlement(nu, 0.25, {{"h_max", 1.5}, {"refine", 1}}) / exact;
  const double fine = square_footing_settlement(nu, 0.25, h_max) / exact;
  std::printf(
      "[ measured ] settlement / closed form: %.4f gmsh at 0.5 m, %.4f gmsh at 0.5 m "
      "refined once, %.4f gmsh at 0.25 m\n",
      coarse, refined, fine);
  EXPECT_LT(coarse, refined);
  EXPECT_LT(refined, 1.0);
  EXPECT_LT(std::abs(refined - fine), 0.5 * std::abs(coarse - fine));
}

}  // namespace
}  // namespace rumble::test
