// The CLM's five parameters from soil properties, footprint size and spacing: the static chain
// rule of docs/physics.md §6.3 (docs/soils.md, "Coupled lumped mass"). A nearest-neighbour chain
//   k_f u_i + k_c (2 u_i - u_{i-1} - u_{i+1}) = F_i
// loaded at one footprint deflects as u_i = G0 r^|i|. Choosing
//   k_f = (1/G0) (1 - r) / (1 + r),   k_c = (1/G0) r / (1 - r^2)
// makes it reproduce the half-space's direct compliance G0 and neighbour ratio r exactly.
// G0 = 1 / K_z (Gazetas' rigid footing, as winkler uses); r from Boussinesq, flexible footprints.
// Dashpots: Lysmer's C_z split in the same proportions (C = (C_z / K_z) K), so that the loaded
// footprint alone shows K_z + i w C_z as a single footing does. Mass: Wolf's trapped mass.
#pragma once

#include "boussinesq.hpp"
#include "half_space.hpp"

namespace rumble::soils {

struct ChainParameters {
  double m_f = 0.0;    // kg
  double k_f = 0.0;    // N/m
  double c_f = 0.0;    // N s/m
  double k_c = 0.0;    // N/m
  double c_c = 0.0;    // N s/m
  double ratio = 0.0;  // r = u1 / u0 [-]
};

/// spacing [m] between footprint centres along the track; 0 for a lone footprint (r = 0).
inline ChainParameters calibrate_chain(const SoilProperties& soil, double length, double width,
                                       double spacing) {
  const FootingImpedance footing = surface_footing(soil, length, width);
  const double r = spacing > 0.0 ? neighbour_compliance_ratio(length, width, spacing) : 0.0;
  const double to_ground = (1.0 - r) / (1.0 + r);  // k_f G0
  const double to_neighbour = r / (1.0 - r * r);   // k_c G0
  return {.m_f = footing.mass,
          .k_f = footing.stiffness * to_ground,
          .c_f = footing.dashpot * to_ground,
          .k_c = footing.stiffness * to_neighbour,
          .c_c = footing.dashpot * to_neighbour,
          .ratio = r};
}

}  // namespace rumble::soils
