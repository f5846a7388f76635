// Euler-Bernoulli beam element (2 nodes; DOFs w, theta = dw/dx per node; w down +): cubic
// Hermite shape functions, consistent mass and stiffness matrices.
#pragma once

#include <array>

namespace rumble::rail_beam {

using Matrix4 = std::array<std::array<double, 4>, 4>;

/// Shape functions at local coordinate xi in [0, 1] of an element of length L [m].
inline std::array<double, 4> shape(double xi, double L) {
  const double x2 = xi * xi, x3 = x2 * xi;
  return {1.0 - 3.0 * x2 + 2.0 * x3, L * (xi - 2.0 * x2 + x3), 3.0 * x2 - 2.0 * x3, L * (x3 - x2)};
}

/// EI [N m^2], L [m].
inline Matrix4 stiffness(double EI, double L) {
  const double k = EI / (L * L * L), L2 = L * L;
  return {{{12 * k, 6 * L * k, -12 * k, 6 * L * k},
           {6 * L * k, 4 * L2 * k, -6 * L * k, 2 * L2 * k},
           {-12 * k, -6 * L * k, 12 * k, -6 * L * k},
           {6 * L * k, 2 * L2 * k, -6 * L * k, 4 * L2 * k}}};
}

/// m [kg/m], L [m].
inline Matrix4 mass(double m, double L) {
  const double c = m * L / 420.0, L2 = L * L;
  return {{{156 * c, 22 * L * c, 54 * c, -13 * L * c},
           {22 * L * c, 4 * L2 * c, 13 * L * c, -3 * L2 * c},
           {54 * c, 13 * L * c, 156 * c, -22 * L * c},
           {-13 * L * c, -3 * L2 * c, -22 * L * c, 4 * L2 * c}}};
}

}  // namespace rumble::rail_beam
