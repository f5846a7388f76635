// 20-point Gauss-Legendre quadrature, for the smooth integrals of the half-space formulas
// (boussinesq.hpp, layered_soil.hpp). Exact for polynomials up to degree 39.
#pragma once

#include <array>

namespace rumble::soils {

/// Integral of f over [a, b] with 20 Gauss-Legendre points.
template <class F>
double gauss_legendre_20(double a, double b, F&& f) {
  // Positive nodes on [-1, 1] and their weights (the rule is symmetric).
  static constexpr std::array<double, 10> kNodes = {
      0.0765265211334973, 0.2277858511416451, 0.3737060887154195, 0.5108670019508271,
      0.6360536807265150, 0.7463319064601508, 0.8391169718222188, 0.9122344282513259,
      0.9639719272779138, 0.9931285991850949};
  static constexpr std::array<double, 10> kWeights = {
      0.1527533871307258, 0.1491729864726037, 0.1420961093183820, 0.1316886384491766,
      0.1181945319615184, 0.1019301198172404, 0.0832767415767048, 0.0626720483341091,
      0.0406014298003869, 0.0176140071391521};
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  double sum = 0.0;
  for (std::size_t k = 0; k < kNodes.size(); ++k)
    sum += kWeights[k] * (f(mid - half * kNodes[k]) + f(mid + half * kNodes[k]));
  return half * sum;
}

}  // namespace rumble::soils
