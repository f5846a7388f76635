// soil_rig.hpp: the winkler and clm plugins as the engine sees them: the .so files found by
// PluginRegistry::load_directory(RUMBLE_TEST_PLUGIN_DIR), each instance a SoilInstance (the
// engine's wrapper that turns every status into an exception with the plugin's message).
// Units: SI throughout, z down (abi.h): F > 0 [N] pushes the soil down, u > 0 [m] is downward.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "plugin/instance.hpp"
#include "plugin/registry.hpp"

namespace rumble::soiltest {

using Eigen::Index;
using Eigen::MatrixXcd;
using Eigen::VectorXd;

/// Every in-tree plugin, loaded once for the process.
const PluginRegistry& registry();
/// The soil type `name` (fails the test when it is missing).
const ComponentType& soil_type(const std::string& name);

/// n sleeper footprints on the track axis at x = i spacing [m], length (across) x width (along)
/// [m]; by default the 2.6 x 0.26 m sleepers at 0.6 m of docs/physics.md §6.3.
std::vector<rumble_footprint> sleeper_row(std::size_t n, double spacing = 0.6, double length = 2.6,
                                          double width = 0.26);

/// A soil of `type` with `params`, label "/soil", that has accepted `layout`.
std::unique_ptr<SoilInstance> make_soil(const std::string& type, const nlohmann::json& params,
                                        const std::vector<rumble_footprint>& layout);

/// The medium soil of docs/physics.md §1.4 (E = 155 MPa, nu = 0.3, rho = 1800 kg/m^3), or
/// another E.
nlohmann::json soil_properties(double E = 155e6, double nu = 0.3, double rho = 1800.0);

/// Static displacements [m] under the footprint forces F [N] (SoilInstance::initialize).
VectorXd static_displacement(SoilInstance& soil, const VectorXd& F);
/// Advance over [t, t + H] with the force varying linearly from f0 (at t) to f1 (at t + H):
/// an order-1 waveform, coefficients {f0, f1 - f0}.
void advance_linear(SoilInstance& soil, double t, double H, const VectorXd& f0, const VectorXd& f1);
/// Advance with the force held at f (order-0 waveform).
void advance_held(SoilInstance& soil, double t, double H, const VectorXd& f);

struct Motion {
  VectorXd u;  // m
  VectorXd v;  // m/s
};
Motion motion(const SoilInstance& soil, Index n);

/// Receptance H(f) [m/N], n x n (u = H F, e^{+i w t}).
MatrixXcd receptance(SoilInstance& soil, double f_hz, Index n);

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
