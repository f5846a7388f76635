// clm: the Coupled Lumped Mass soil (Kouroussis, Gazetas, Anastasopoulos, Conti, Verlinden,
// Soil Dyn. Earthq. Eng. 31(12), 2011): per footprint a mass m_f, a spring k_f and a dashpot c_f
// to the ground, and a spring k_c and a dashpot c_c to each neighbour. The five parameters are
// given, or calibrated from soil properties, footprint size and spacing (chain_calibration.hpp,
// docs/soils.md). A massless soil under explicit coupling closes an algebraic loop through the
// ballast and soil dashpots (docs/decisions/0004, docs/soils.md §8): give m_f when it is soft.
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "chain_calibration.hpp"
#include "chain_layout.hpp"
#include "layered_soil.hpp"
#include "lumped_soil.hpp"
#include "soil_params.hpp"

namespace {

using rumble::soils::LumpedParameters;
using rumble::soils::SoilParams;

class Clm final : public rumble::soils::LumpedSoil {
 public:
  static constexpr const char* kTypeName = "clm";
  static constexpr const char* kSummary =
      "Coupled Lumped Mass soil (Kouroussis 2011): mass-spring-dashpot per footprint coupled to "
      "its neighbours; given or calibrated from E, nu, rho";
  /// Takes any step it is given (a coupler need not keep the other side's checkpoint for it).
  static constexpr std::uint64_t kCapabilities = rumble::kCapNeverRefuses;
  static const char* params_schema() {
    static const std::string schema = std::string(R"schema({
  "$schema": "http://json-schema.org/draft-07/schema#",
  "type": "object",
  "additionalProperties": false,
  "description": "give m_f, k_f, c_f, k_c and c_c, or E, nu and rho (and optionally layers and m_f)",
  "oneOf": [
    {"required": ["m_f", "k_f", "c_f", "k_c", "c_c"], "not": {"description": "gives the five parameters together with soil properties; give either m_f, k_f, c_f, k_c and c_c (direct) or E, nu and rho (from soil properties), not both", "anyOf": [{"required": ["E"]}, {"required": ["nu"]}, {"required": ["rho"]}, {"required": ["layers"]}]}},
    {"required": ["E", "nu", "rho"], "not": {"description": "gives soil properties together with k_f, c_f, k_c or c_c; give either the five parameters (direct) or E, nu and rho (from soil properties, optionally with m_f), not both", "anyOf": [{"required": ["k_f"]}, {"required": ["c_f"]}, {"required": ["k_c"]}, {"required": ["c_c"]}]}}
  ],
  "properties": {
    "m_f": {"type": "number", "minimum": 0, "maximum": 1e6, "description": "mass per footprint [kg]; from soil properties: Wolf's cone trapped mass (Wolf & Deeks 2004) 2.4 (nu - 1/3) rho pi r0^3, r0 = sqrt(A / pi), for nu > 1/3, else 0 (a value given with E, nu, rho replaces it); [0, 1e6] kg: the trapped mass of a sleeper's footprint is some 100 kg (1e5 kg under a 10 m x 2 m footprint of dense soil)"},
    "k_f": {"type": "number", "minimum": 1e4, "maximum": 1e13, "description": "spring from each footprint to the ground [N/m]; from soil properties: K_z (1 - r) / (1 + r), K_z Gazetas' (1991) rigid-rectangle stiffness 2 G L / (1 - nu) (0.73 + 1.54 (B/L)^0.75) of the 2L x 2B footprint, r the neighbour/direct ratio of Boussinesq displacements of flexible uniformly loaded footprints at the spacing (static chain rule); [1e4, 1e13] N/m: Gazetas' K_z of a sleeper's footprint is about 1e6 on peat (E = 1 MPa) and 1e10 on hard rock (E = 100 GPa)"},
    "c_f": {"type": "number", "minimum": 0, "maximum": 1e10, "description": "dashpot from each footprint to the ground [N s/m]; from soil properties: C_z (1 - r) / (1 + r), C_z = rho V_La A, V_La = 3.4 c_s / (pi (1 - nu)) (Lysmer's analog); [0, 1e10] N s/m: Lysmer's C_z of a sleeper's footprint is about 2e4 on peat and 1e7 on hard rock"},
    "k_c": {"type": "number", "minimum": 0, "maximum": 1e13, "description": "spring between neighbouring footprints [N/m]; from soil properties: K_z r / (1 - r^2); [0, 1e13] N/m: as k_f's (a neighbour's share of K_z)"},
    "c_c": {"type": "number", "minimum": 0, "maximum": 1e10, "description": "dashpot between neighbouring footprints [N s/m]; from soil properties: C_z r / (1 - r^2); [0, 1e10] N s/m: as c_f's (a neighbour's share of C_z)"},)schema") +
                                      rumble::soils::kSoilPropertiesSchema + "," +
                                      rumble::soils::kMaxStepSchema + R"schema(
  }
})schema";
    return schema.c_str();
  }

  Clm(const std::string& params_json, const rumble::Host& /*host*/)
      : Clm(SoilParams(params_json, kTypeName)) {}

 private:
  explicit Clm(const SoilParams& p)
      : LumpedSoil(kTypeName, p.has("max_step") ? p.positive("max_step", "s") : 0.0),
        direct_(p.direct({"k_f", "c_f", "k_c", "c_c"}, "m_f, k_f, c_f, k_c and c_c")) {
    if (direct_ || p.has("m_f")) mass_ = p.non_negative("m_f", "kg");
    if (direct_) {
      given_ = {.m_f = mass_.value_or(0.0),
                .k_f = p.positive("k_f", "N/m"),
                .c_f = p.non_negative("c_f", "N s/m"),
                .k_c = p.non_negative("k_c", "N/m"),
                .c_c = p.non_negative("c_c", "N s/m")};
      if (given_.m_f == 0.0 && given_.c_f == 0.0 && given_.c_c > 0.0) {
        // The chain's uniform motion would have neither inertia nor a dashpot to the ground.
        throw std::invalid_argument(
            "clm: with m_f = 0 and c_c > 0 the ground dashpot c_f must be > 0, got 0; give "
            "m_f > 0, c_f > 0 or c_c = 0");
      }
    } else {
      half_space_ = p.half_space();
      layers_ = p.layers();
      set_slowest_wave_speeds(rumble::soils::slowest_wave_speeds(layers_, half_space_));
    }
  }

  LumpedParameters parameters(const std::vector<rumble::Footprint>& footprints) const override {
    const double spacing = rumble::soils::chain_spacing(footprints, !direct_);
    const rumble::soils::ChainParameters c = direct_ ? given_ : calibrated(footprints[0], spacing);
    const auto n = static_cast<Eigen::Index>(footprints.size());
    return {.mass = Eigen::VectorXd::Constant(n, c.m_f),
            .stiffness = Eigen::VectorXd::Constant(n, c.k_f),
            .damping = Eigen::VectorXd::Constant(n, c.c_f),
            .coupling_stiffness = c.k_c,
            .coupling_damping = c.c_c};
  }

  rumble::soils::ChainParameters calibrated(const rumble::Footprint& f, double spacing) const {
    std::ostringstream m;
    if (!(f.length > 0.0 && f.width > 0.0) || !std::isfinite(f.length * f.width)) {
      m << "clm: footprints are " << f.length << " m x " << f.width
        << " m; calibrating from soil properties needs a length and width > 0";
    } else if (spacing > 0.0 && spacing < f.width) {
      m << "clm: footprints overlap: the spacing " << spacing << " m is less than their width "
        << f.width << " m along the track; calibrating from soil properties needs footprints "
        << "that do not overlap";
    } else {
      const auto soil =
          rumble::soils::equivalent_properties(layers_, half_space_, f.length, f.width);
      auto c = rumble::soils::calibrate_chain(soil, f.length, f.width, spacing);
      c.m_f = mass_.value_or(c.m_f);
      return c;
    }
    throw std::invalid_argument(m.str());
  }

  bool direct_;
  rumble::soils::ChainParameters given_;  // direct
  std::optional<double> mass_;            // kg; replaces Wolf's trapped mass when given
  rumble::soils::SoilProperties half_space_;
  std::vector<rumble::soils::SoilLayer> layers_;
};

}  // namespace

RUMBLE_PLUGIN("clm", "0.3.0", Clm)
