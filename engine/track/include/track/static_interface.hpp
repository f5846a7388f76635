// The track/soil static interface problem: find the footprint settlements u [m] with
// u = S(T(u)), where T (the track: vehicles in equilibrium on the rail, Hertz contacts, ballast)
// gives the footprint forces [N] for given settlements, and S (the soil) the settlements under
// given footprint forces. T is cheap and mildly non-linear; S is linear and costly (a FEM soil's
// static solve: seconds to minutes at 1e6 DOFs), so the method counts soil solves.
//
// The plain iteration u <- S(T(u)) diverges on soft soils (the loop gain, ballast stiffness over
// the soil's, is ~10). Aitken's relaxation needed 16-19 soil solves on the paper's soft soil, and
// IQN-ILS as many: both learn the track's side, which is known, as well as the soil's. Here the
// track is linearised exactly (a finite-difference Jacobian J_T of T, n cheap track evaluations)
// and only the soil is learnt, by a surrogate S~ that reproduces every soil solve so far (a
// multi-secant model, as in IQN-IMVJ, Lindner et al. 2015) around a prior P elsewhere:
//
//   S~ x = u_k + dU c + P (x - f_k - dF c),   c = argmin |dF c - (x - f_k)|,
//
// (f_k, u_k) the latest soil solve, dF and dU the differences of the earlier ones from it (each
// scaled to a unit force difference). The prior P = a I + b G, a [m/N] and b [m^2/N] >= 0 fitted
// to the first solve, mixes a local flexibility (a Winkler soil: exact at once) with the half-space
// shape G between the footprints (footprint_flexibility.hpp), which halves the solves on a
// continuum soil. Each outer step solves the surrogate coupled problem x = S~(T(x)) to
// convergence (chord Newton with I - S~ J_T: track evaluations only), then asks the soil once.
// S is linear, so S~ is exact on the span of the forces seen; the error left is the soil's
// response, less the prior's, to the force changes outside it, which shrink each step.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <vector>

namespace rumble {

/// out = map(in), both n values: the track (settlements [m] -> forces [N]) or the soil (forces
/// -> settlements).
using InterfaceMap = std::function<void(const std::vector<double>& in, std::vector<double>& out)>;

struct InterfaceTolerances {
  double relative = 1e-9;   // [-] of the largest settlement: far below any physical effect
  double absolute = 1e-15;  // m: a soil that does not settle
  int max_soil_solves = 50;
};

struct InterfaceStatics {
  int soil_solves = 0;
  int track_evaluations = 0;
};

/// Finds u with u = soil(track(u)) to tol, starting from u = 0; shape: G of the header [1/m],
/// n x n. On return u is the soil's last
/// settlement and force = track(u), the last track evaluation (so the track's state is that of
/// u). Throws RunError when it does not converge in tol.max_soil_solves soil solves or
/// a map returns a non-finite value.
InterfaceStatics solve_interface_statics(const InterfaceMap& track, const InterfaceMap& soil,
                                         const Eigen::MatrixXd& shape, std::vector<double>& u,
                                         std::vector<double>& force,
                                         const InterfaceTolerances& tol = {});

}  // namespace rumble
