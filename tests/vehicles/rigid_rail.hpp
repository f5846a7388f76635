// rigid_rail.hpp: reference computations on a vehicle: statics and modes with the wheels held on a
// rigid rail (z_w(q) = 0), and finite-difference tangents.
#pragma once

#include "vehicle_harness.hpp"

namespace rumble::test {

struct Equilibrium {
  VectorXd q;              // static DOFs [m, rad]
  VectorXd contact_force;  // F_w >= 0 per wheel [N]
  int iterations = 0;
};

/// Solves f(q, 0) = J(q)^T F, z(q) = 0 by Newton on (q, F) with the plugin's tangent; the result
/// is an equilibrium to round-off (residual < 1e-9 of the total weight), whatever the tangent's
/// accuracy, which only affects the iteration count. Throws when it does not converge.
Equilibrium rigid_rail_statics(TestVehicle& v);

/// Undamped natural frequencies [Hz], ascending, of small motions about q with the wheels held on
/// the rigid rail: generalized eigenproblem of K and M reduced to the null space of J. Neglects
/// the constraint curvature F_w d2z_w/dq2, which is zero when each wheel sits on a body moved by
/// translations only (all vehicles in these tests).
VectorXd rigid_rail_frequencies_hz(TestVehicle& v, const VectorXd& q);

/// K = -df/dq and C = -df/dq' by central differences with steps h_q [m, rad] and h_qd [m/s].
void central_difference_tangent(TestVehicle& v, const VectorXd& q, const VectorXd& qd, double h_q,
                                double h_qd, MatrixXd& k, MatrixXd& c);

}  // namespace rumble::test
