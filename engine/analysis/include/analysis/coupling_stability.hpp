// Stability of the explicit coupling schemes (issue #10, "the paper's finding"; issue #29
// item 5): the growth per macro step of gauss_seidel (track first) and jacobi, linearized at
// the static state with the vehicles at rest, for a scenario's vehicle/track and its soil. A
// growth above 1 means a perturbation grows by that factor every macro step: the run diverges.
//
// The coupled system is stepped as a run steps it: the engine's own vehicle/track (its Newmark
// micro-steps and Hertz contacts) and the soil plugin itself (its own integrator, sub-steps and
// consistent start of each step: the analysis once integrated the soil's linear matrices at the
// track's micro-step instead, which read 0.9986 for a massless soil that diverges at 1.011 per
// step, and 1.029 for one growing 1.041), the inputs over the step as gauss_seidel and jacobi
// feed them with the given extrapolation order (0: held, 1-2: from the previous steps'
// outputs) and, for gauss_seidel, interpolation order (0: the track's new forces held, 1:
// linear from the old ones). A tiny random perturbation of the track's static state is followed
// over hundreds to thousands of macro steps against the unperturbed run, until the growth of
// its dominant mode has settled or it leaves the linear range; the growth is the least-squares
// slope of its logarithm over the second half. Nothing is renormalised (the soil's state is the
// plugin's own, not a vector: a FEM soil keeps checkpoints itself), so any soil can be analysed,
// and a FEM soil costs its own steps: seconds for a 3e4-DOF mesh. Stable systems read
// 0.999-1.000 (the average-acceleration rule does not damp the track's modes).
// docs/couplers.md compares the analysis with measured runs.
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
  double spectral_radius = 0.0;  // [-] growth per macro step of the dominant mode
  std::size_t state_size = 0;    // the quantities followed (the track's state, footprint u, v)
};

/// For every macro step H [s] and both schemes. The soil is taken from `built` when validation
/// built it (plugin/built_soils.hpp).
std::vector<StabilityPoint> coupling_stability(scenario::RunSpec spec,
                                               const PluginRegistry& registry,
                                               const std::vector<double>& macro_steps,
                                               const StabilityInputs& inputs = {},
                                               BuiltSoils* built = nullptr);

}  // namespace rumble
