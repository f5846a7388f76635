// Hertz wheel/rail contact: F = C_H delta^1.5 (delta > 0), the constant C_H from the wheel's
// rolling radius and the rail crown's transverse radius (Johnson, Contact Mechanics, 1985, §4.2;
// docs/physics.md §7). Both bodies are of the same material (E, nu).
#pragma once

namespace rumble {

/// The elliptic contact patch of two bodies pressed together by a load P (Johnson §4.2).
struct HertzContact {
  double semi_major = 0.0;    // a [m], along the direction of the smaller relative curvature
  double semi_minor = 0.0;    // b [m]
  double eccentricity = 0.0;  // e = sqrt(1 - b^2/a^2), 0 for a circle
  double approach = 0.0;      // delta [m], mutual approach of distant points
};

/// Exact Hertz solution for wheel rolling radius R_w [m], rail crown radius R_r [m], Young's
/// modulus E [Pa], Poisson ratio nu and load P [N] >= 0. Relative curvatures A = 1/(2 R_w),
/// B = 1/(2 R_r); the eccentricity solves B/A = (E(e)/(1 - e^2) - K(e)) / (K(e) - E(e)) with the
/// complete elliptic integrals K, E. Throws std::invalid_argument on bad input (see
/// hertz_constant) or a negative load.
HertzContact hertz_contact(double wheel_radius, double rail_radius, double E, double nu,
                           double load);

/// Exact Hertz constant C_H = P / delta^1.5 [N/m^1.5] (independent of P).
/// Throws std::invalid_argument for non-positive (or non-finite) radii or E, or nu outside
/// [0, 0.5), with the text "Hertz contact: <what> must be ..., got <value>".
double hertz_constant(double wheel_radius, double rail_radius, double E, double nu);

/// The common approximation C_H = 2E / (3 (1 - nu^2)) sqrt(sqrt(R_w R_r)): a sphere of radius
/// sqrt(R_w R_r). Exact for R_w = R_r; low by at most 0.5 % for R_r / R_w between 0.65 and 1.6
/// (1 % at 0.5 and 2), by 6 % for R_w = 0.46 m on R_r = 0.08 m. Same checks as hertz_constant.
double hertz_constant_approx(double wheel_radius, double rail_radius, double E, double nu);

/// Static approach delta = (P / C_H)^(2/3) [m] under load P [N] >= 0.
/// Throws std::invalid_argument for C_H <= 0 or P < 0.
double static_approach(double hertz_constant, double load);

/// Linearized contact stiffness dF/d delta = 1.5 C_H^(2/3) P^(1/3) [N/m] at load P [N] >= 0.
/// Throws std::invalid_argument for C_H <= 0 or P < 0.
double linearized_stiffness(double hertz_constant, double load);

}  // namespace rumble
