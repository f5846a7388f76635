// The static flexibility between sleeper footprints on a homogeneous elastic half-space, up to
// its material factor: the mean settlement of footprint i under a unit force spread uniformly
// over footprint j is (1 - nu^2) / (pi E) * G_ij (Boussinesq), and this gives G [1/m].
//
// Used only as the shape of the soil the track/soil static iteration expects before it has
// asked the soil anything (static_interface.hpp): its accuracy changes how many soil solves the
// iteration needs, never its answer. So the integral is the cheap one: each footprint is cut into
// near-square cells, cells interact through 1/r between their centres, and a cell with itself
// through the mean of 1/r over a square of its area (2.9732 / side).
#pragma once

#include <rumble/abi.h>

#include <Eigen/Core>
#include <vector>

namespace rumble {

/// G [1/m], n x n, symmetric, for the n footprints.
Eigen::MatrixXd half_space_flexibility_shape(const std::vector<rumble_footprint>& footprints);

}  // namespace rumble
