// Reading soil properties (E, nu, rho, optional layers) from a soil's params, and the
// equivalent homogeneous properties of a layered soil (docs/soils.md, "Layered soils").
#pragma once

#include <rumble/params.hpp>
#include <string>

#include "half_space.hpp"

namespace rumble::soils {

/// JSON Schema fragment (properties) shared by the soils that derive their parameters from
/// soil properties.
inline constexpr const char* kSoilPropertiesSchema = R"schema(
    "E": {"type": "number", "exclusiveMinimum": 0, "description": "Young's modulus of the (lowest) soil [Pa]"},
    "nu": {"type": "number", "minimum": 0, "exclusiveMaximum": 0.5, "description": "Poisson ratio [-], in [0, 0.5)"},
    "rho": {"type": "number", "exclusiveMinimum": 0, "description": "density [kg/m^3]"},
    "layers": {
      "type": "array",
      "description": "layers above the half-space (E, nu, rho), top first; replaced by thickness-weighted equivalent properties over a depth equal to the footprint length",
      "items": {
        "type": "object",
        "additionalProperties": false,
        "required": ["thickness", "E", "nu", "rho"],
        "properties": {
          "thickness": {"type": "number", "exclusiveMinimum": 0, "description": "layer thickness [m]"},
          "E": {"type": "number", "exclusiveMinimum": 0, "description": "Young's modulus [Pa]"},
          "nu": {"type": "number", "minimum": 0, "exclusiveMaximum": 0.5, "description": "Poisson ratio [-]"},
          "rho": {"type": "number", "exclusiveMinimum": 0, "description": "density [kg/m^3]"}
        }
      }
    })schema";

/// Equivalent homogeneous properties over [0, depth] [m]: each property averaged with the
/// thickness of each layer inside that depth as weight, the half-space filling the rest.
/// A first-order rule (the stress bulb under a footprint reaches about its larger dimension);
/// calibrate against a layered FEM soil's receptance where it matters (`rumble calibrate`).
inline SoilProperties equivalent_properties(const Params& p, double depth) {
  SoilProperties half_space{p.get<double>("E"), p.get<double>("nu"), p.get<double>("rho")};
  check_properties(half_space, "params");
  if (!p.has("layers")) return half_space;
  SoilProperties sum{};
  double top = 0.0;
  const auto& layers = p.json().at("layers");
  for (std::size_t i = 0; i < layers.size() && top < depth; ++i) {
    const auto& l = layers[i];
    const SoilProperties s{l.at("E").get<double>(), l.at("nu").get<double>(),
                           l.at("rho").get<double>()};
    check_properties(s, "params/layers/" + std::to_string(i));
    const double t = std::min(l.at("thickness").get<double>(), depth - top);
    sum.E += t * s.E;
    sum.nu += t * s.nu;
    sum.rho += t * s.rho;
    top += t;
  }
  const double rest = depth - top;
  sum.E += rest * half_space.E;
  sum.nu += rest * half_space.nu;
  sum.rho += rest * half_space.rho;
  return {sum.E / depth, sum.nu / depth, sum.rho / depth};
}

}  // namespace rumble::soils
