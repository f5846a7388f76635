// soil_rig.hpp: the winkler and clm plugins as the engine sees them, for the tests of the
// engine's side (calibration, the CLI): the soils and the steps every soil test takes are
// tests/soils/soil_harness's (each soil a SoilInstance from the engine's PluginRegistry), named
// here in rumble::soiltest; what is added is what only these tests use.
// Units: SI throughout, z down (abi.h): F > 0 [N] pushes the soil down, u > 0 [m] is downward.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "soil_harness.hpp"

namespace rumble::soiltest {

using Eigen::Index;
using Eigen::MatrixXcd;
using Eigen::VectorXd;

using test::advance_held;
using test::advance_linear;
using test::Motion;
using test::motion;
using test::receptance;
using test::sleeper_row;
using test::soil_type;
using test::static_displacement;

/// A soil of `type` with `params`, label "/soil", that has accepted `layout` (lay_soil, as the
/// engine lays its soils: LayoutRefused when it refuses the layout).
std::unique_ptr<SoilInstance> make_soil(const std::string& type, const nlohmann::json& params,
                                        const std::vector<rumble_footprint>& layout);

/// The medium soil of docs/physics.md §1.4 (E = 155 MPa, nu = 0.3, rho = 1800 kg/m^3), or
/// another E.
nlohmann::json soil_properties(double E = 155e6, double nu = 0.3, double rho = 1800.0);

/// The five parameters of a nearest-neighbour lumped chain, read back from a soil through its
/// receptance only: the dynamic stiffness D(w) = H(w)^-1 = K - w^2 M + i w C is tridiagonal, so
/// k_c = -Re D_01(0), k_f = Re D_11(0) - 2 k_c (footprint 1 has two neighbours), c_c and c_f
/// likewise from Im D(w) / w, m_f = (Re D_11(0) - Re D_11(w)) / w^2. For winkler (no coupling)
/// k_c = c_c = 0 and footprint 0 is used.
struct Lumped {
  double m_f = 0.0;  // kg
  double k_f = 0.0;  // N/m
  double c_f = 0.0;  // N s/m
  double k_c = 0.0;  // N/m
  double c_c = 0.0;  // N s/m
};
Lumped lumped_parameters(SoilInstance& soil, Index n, double f_probe_hz = 10.0);

/// Direct clm params {m_f, k_f, c_f, k_c, c_c}.
nlohmann::json clm_params(const Lumped& p);

}  // namespace rumble::soiltest
