// Hertz wheel/rail contact: F = C_H delta^1.5 (delta > 0), the constant C_H from the wheel's
// rolling radius and the rail crown's transverse radius (Johnson, Contact Mechanics, 1985, §4.2).
#pragma once

namespace rumble {

/// Exact Hertz constant C_H [N/m^1.5] for steel-like bodies of Young's modulus E [Pa] and
/// Poisson ratio nu, wheel rolling radius R_w [m] and rail crown radius R_r [m] (relative
/// curvatures A = 1/(2 R_w), B = 1/(2 R_r); elliptic contact; complete elliptic integrals).
/// Throws std::invalid_argument for non-positive radii or E, or nu outside [0, 0.5).
double hertz_constant(double wheel_radius, double rail_radius, double E, double nu);

/// The common approximation C_H = 2E / (3 (1 - nu^2)) sqrt(sqrt(R_w R_r)) (sphere of radius
/// sqrt(R_w R_r)); within 0.5 % of the exact value for R_r / R_w between 0.5 and 1.5.
double hertz_constant_approx(double wheel_radius, double rail_radius, double E, double nu);

/// Static approach delta = (P / C_H)^(2/3) [m] under load P [N].
double static_approach(double hertz_constant, double load);

/// Linearized contact stiffness dF/d delta = 1.5 C_H^(2/3) P^(1/3) [N/m] at load P [N].
double linearized_stiffness(double hertz_constant, double load);

}  // namespace rumble
