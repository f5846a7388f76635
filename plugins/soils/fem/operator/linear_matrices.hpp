// The FEM soil's equations as matrices (abi.h rumble_matrix), for the monolithic reference and
// `rumble stability`: the system the explicit and implicit integrators step,
//   M w'' + C w' + (K + S) w = B F,   u = B^T w,   C = a0 M + a1 K + D,
// with M the lumped mass (3 equal DOFs per node), K the elastic stiffness, S and D the absorbing
// boundary's spring and dashpot blocks (springs only where they act), B the footprint weights on
// the vertical DOFs (footprint_loads.hpp). A fixed node's DOFs keep an identity row and column in
// K and nothing in M, C or B, so they stay at 0 and the matrices stay symmetric and K positive
// definite.
#pragma once

#include <rumble/abi.h>

#include <rumble/plugin.hpp>

#include "operator/footprint_loads.hpp"
#include "operator/soil_operator.hpp"

namespace rumble::fem {

/// One of M, C, K, B as a CSC matrix (rows sorted per column). a0 [1/s], a1 [s]: Rayleigh.
void linear_matrix(const SoilOperator& op, const FootprintWeights& weights, double a0, double a1,
                   rumble_matrix which, CscMatrix& out);

}  // namespace rumble::fem
