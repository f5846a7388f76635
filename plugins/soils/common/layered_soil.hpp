// Layered soils reduced to equivalent homogeneous properties under one footprint
// (docs/soils.md, "Layered soils"). The classical layer-summation settlement
// s = sum_j int_layer_j sigma_z(z) / E_j dz, with sigma_z the Boussinesq vertical stress under
// the footprint centre, defines the equivalent modulus as the stress-weighted harmonic mean:
//   1 / E_eq = sum_j w_j / E_j,   w_j = int_layer_j sigma_z dz / int_0^inf sigma_z dz,
// so a soft top layer dominates as it does in reality. nu and rho are averaged with the same
// weights. First-order: calibrate against a layered FEM soil where it matters.
#pragma once

#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <limits>
#include <vector>

#include "boussinesq.hpp"
#include "half_space.hpp"

namespace rumble::soils {

struct SoilLayer {
  double thickness = 0.0;  // m
  SoilProperties properties;
};

/// int_{z_top}^{z_bottom} sigma_z(z) / q dz [m] under the centre of a length x width footprint;
/// z_bottom may be infinite. The map z = s t / (1 - t), s = sqrt(area), makes the integrand
/// bounded on t in [0, 1) (sigma_z decays as 1/z^2); 8 panels of 20 Gauss points are converged
/// to 1e-12 relative.
inline double stress_weight(double length, double width, double z_top, double z_bottom) {
  const double s = std::sqrt(length * width);
  const double t0 = z_top / (s + z_top);
  const double t1 = std::isinf(z_bottom) ? 1.0 : z_bottom / (s + z_bottom);
  constexpr int kPanels = 8;
  double sum = 0.0;
  for (int p = 0; p < kPanels; ++p) {
    const double a = t0 + (t1 - t0) * p / kPanels, b = t0 + (t1 - t0) * (p + 1) / kPanels;
    sum += boost::math::quadrature::gauss<double, 20>::integrate(
        [&](double t) {
          return centre_vertical_stress(length, width, s * t / (1.0 - t)) * s /
                 ((1.0 - t) * (1.0 - t));
        },
        a, b);
  }
  return sum;
}

/// Equivalent homogeneous properties of `layers` (top first) over `half_space`, under a
/// length x width footprint [m].
inline SoilProperties equivalent_properties(const std::vector<SoilLayer>& layers,
                                            const SoilProperties& half_space, double length,
                                            double width) {
  if (layers.empty()) return half_space;
  double weight = 0.0, compliance = 0.0, nu = 0.0, rho = 0.0;
  const auto add = [&](const SoilProperties& p, double w) {
    weight += w;
    compliance += w / p.E;
    nu += w * p.nu;
    rho += w * p.rho;
  };
  double top = 0.0;
  for (const SoilLayer& layer : layers) {
    add(layer.properties, stress_weight(length, width, top, top + layer.thickness));
    top += layer.thickness;
  }
  add(half_space, stress_weight(length, width, top, std::numeric_limits<double>::infinity()));
  return {weight / compliance, nu / weight, rho / weight};
}

}  // namespace rumble::soils
