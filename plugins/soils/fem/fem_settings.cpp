// The settings' derived values: the damping's coefficients and mechanisms, the layer's shift, the
// soil at a depth (reading the params: read_settings.cpp).
#include "fem_settings.hpp"

#include <cmath>
#include <numbers>

namespace rumble::fem {

double DampingRequest::mass_coefficient() const {
  if (maxwell) return 0.0;
  const double w1 = 2.0 * std::numbers::pi * f_low, w2 = 2.0 * std::numbers::pi * f_high;
  return 2.0 * ratio * w1 * w2 / (w1 + w2);
}

double DampingRequest::stiffness_coefficient() const {
  if (maxwell) return 0.0;
  const double w1 = 2.0 * std::numbers::pi * f_low, w2 = 2.0 * std::numbers::pi * f_high;
  return 2.0 * ratio / (w1 + w2);
}

MaxwellDamping DampingRequest::maxwell_mechanisms() const {
  if (!maxwell || ratio == 0.0) return {};
  return MaxwellDamping::fit(ratio, f_low, f_high, mechanisms);
}

double DampingRequest::relaxed_modulus_factor() const {
  const MaxwellDamping d = maxwell_mechanisms();
  if (d.mechanisms() == 0) return 1.0;
  return 1.0 / d.modulus(2.0 * std::numbers::pi * std::sqrt(f_low * f_high)).real();
}

double BoundaryRequest::pml_shift() const {
  return 2.0 * std::numbers::pi * pml_shift_frequency;
}

const soils::SoilProperties& FemSettings::properties_at(double depth) const {
  double bottom = 0.0;
  for (const soils::SoilLayer& l : layers) {
    bottom += l.thickness;
    if (depth < bottom) return l.properties;
  }
  return half_space;
}

}  // namespace rumble::fem
