// Stability of the explicit coupling schemes (issue #10, "the paper's finding"): the spectral
// radius of one macro step of gauss_seidel (track first) and jacobi, linearized at the static
// state with the vehicles at rest, for a scenario's vehicle/track and its soil as given by the
// soil's linear matrices (M, C, K, B; abi.h rumble_matrix). A radius above 1 means a
// perturbation grows by that factor every macro step: the run diverges.
//
// The one-step map is the engine's own vehicle/track (its Newmark micro-steps and Hertz
// contacts) and the soil's equations stepped with Newmark at the same micro-step, the inputs over
// the step as gauss_seidel and jacobi feed them with the given extrapolation order (0: held,
// 1-2: from the previous steps' outputs, which then belong to the state) and, for gauss_seidel,
// interpolation order (0: the track's new forces held, 1: linear from the old ones). Its
// spectral radius is found by power iteration on that map
// (a small perturbation of the static state, stepped and renormalised), not by forming the
// matrix: the map's entries span 20 orders of magnitude (stiff rotational modes of the rail) and
// a dense eigenvalue solver returned radii of 5 for a track that is stable on its own. Stable
// maps read 0.999-1.000 (the average-acceleration rule does not damp the track's modes).
//
// The soil plugin's own integrator is not the one used here (a massless footprint's velocity in
// particular); docs/couplers.md compares the analysis with measured runs.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "plugin/built_soils.hpp"
#include "plugin/registry.hpp"
#include "scenario/run_spec.hpp"

namespace rumble {

/// How both schemes feed their inputs over a macro step (their params `extrapolation`, 0..2, and
/// gauss_seidel's `interpolation`, 0..1).
struct StabilityInputs {
  std::uint32_t extrapolation = 0;
  std::uint32_t interpolation = 0;
};

struct StabilityPoint {
  std::string scheme;            // "gauss_seidel" or "jacobi"
  double macro_step = 0.0;       // s
  double spectral_radius = 0.0;  // [-] of the one-step map
  std::size_t state_size = 0;    // its dimension
};

/// For every macro step H [s] and both schemes. Throws ConfigError for a soil without linear
/// matrices. The soil is taken from `built` when validation built it (plugin/built_soils.hpp).
std::vector<StabilityPoint> coupling_stability(scenario::RunSpec spec,
                                               const PluginRegistry& registry,
                                               const std::vector<double>& macro_steps,
                                               const StabilityInputs& inputs = {},
                                               BuiltSoils* built = nullptr);

}  // namespace rumble
