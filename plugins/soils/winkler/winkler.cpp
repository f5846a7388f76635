// winkler: one spring-dashpot, with an optional participating mass, per footprint; footprints
// do not interact. Given directly (k, c, m), or per footprint from soil properties and the
// footprint's size: Gazetas (1991) rigid-rectangle stiffness, Lysmer's analog radiation
// dashpot, Wolf's cone trapped mass (docs/soils.md).
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "half_space.hpp"
#include "layered_soil.hpp"
#include "lumped_soil.hpp"
#include "soil_params.hpp"

namespace {

using rumble::soils::LumpedParameters;
using rumble::soils::SoilParams;

class Winkler final : public rumble::soils::LumpedSoil {
 public:
  static constexpr const char* kTypeName = "winkler";
  static constexpr const char* kSummary =
      "one spring-dashpot (+ optional mass) per footprint, given or from E, nu, rho (Gazetas "
      "stiffness, Lysmer dashpot, Wolf trapped mass)";
  /// Takes any step it is given (a coupler need not keep the other side's checkpoint for it).
  static constexpr std::uint64_t kCapabilities = rumble::kCapNeverRefuses;
  static const char* params_schema() {
    static const std::string schema = std::string(R"schema({
  "$schema": "http://json-schema.org/draft-07/schema#",
  "type": "object",
  "additionalProperties": false,
  "description": "give k and c (and optionally m), or E, nu and rho (and optionally layers and m)",
  "oneOf": [
    {"required": ["k", "c"], "not": {"description": "gives k and c together with soil properties; give either k and c (direct) or E, nu and rho (from soil properties), not both", "anyOf": [{"required": ["E"]}, {"required": ["nu"]}, {"required": ["rho"]}, {"required": ["layers"]}]}},
    {"required": ["E", "nu", "rho"], "not": {"description": "gives soil properties together with k or c; give either k and c (direct) or E, nu and rho (from soil properties), not both", "anyOf": [{"required": ["k"]}, {"required": ["c"]}]}}
  ],
  "properties": {
    "k": {"type": "number", "minimum": 1e4, "maximum": 1e13, "description": "spring per footprint [N/m]; from soil properties: Gazetas (1991) rigid rectangle 2L x 2B on a half-space, K_z = 2 G L / (1 - nu) (0.73 + 1.54 chi^0.75), chi = B / L <= 1; [1e4, 1e13] N/m: Gazetas' K_z of a sleeper's footprint is about 1e6 on peat (E = 1 MPa) and 1e10 on hard rock (E = 100 GPa)"},
    "c": {"type": "number", "minimum": 0, "maximum": 1e10, "description": "dashpot per footprint [N s/m]; from soil properties: Lysmer's analog (Gazetas 1991), C_z = rho V_La A, V_La = 3.4 c_s / (pi (1 - nu)) [m/s], A the footprint area [m^2]; [0, 1e10] N s/m: Lysmer's C_z of a sleeper's footprint is about 2e4 on peat and 1e7 on hard rock"},
    "m": {"type": "number", "minimum": 0, "maximum": 1e6, "description": "participating mass per footprint [kg]; default 0 with k and c; from soil properties: Wolf's cone trapped mass (Wolf & Deeks 2004) 2.4 (nu - 1/3) rho pi r0^3, r0 = sqrt(A / pi), for nu > 1/3, else 0; [0, 1e6] kg: the trapped mass of a sleeper's footprint is some 100 kg (1e5 kg under a 10 m x 2 m footprint of dense soil)"},)schema") +
                                      rumble::soils::kSoilPropertiesSchema + "," +
                                      rumble::soils::kMaxStepSchema + R"schema(
  }
})schema";
    return schema.c_str();
  }

  Winkler(const std::string& params_json, const rumble::Host& /*host*/)
      : Winkler(SoilParams(params_json, kTypeName)) {}

 private:
  explicit Winkler(const SoilParams& p)
      : LumpedSoil(kTypeName, p.has("max_step") ? p.positive("max_step", "s") : 0.0),
        direct_(p.direct({"k", "c"}, "k and c")) {
    if (p.has("m")) mass_ = p.non_negative("m", "kg");
    if (direct_) {
      stiffness_ = p.positive("k", "N/m");
      damping_ = p.non_negative("c", "N s/m");
    } else {
      half_space_ = p.half_space();
      layers_ = p.layers();
      set_slowest_wave_speeds(rumble::soils::slowest_wave_speeds(layers_, half_space_));
    }
  }

  LumpedParameters parameters(const std::vector<rumble::Footprint>& footprints) const override {
    const auto n = static_cast<Eigen::Index>(footprints.size());
    LumpedParameters p{.mass = Eigen::VectorXd::Constant(n, mass_.value_or(0.0)),
                       .stiffness = Eigen::VectorXd::Constant(n, stiffness_),
                       .damping = Eigen::VectorXd::Constant(n, damping_)};
    if (direct_) return p;
    for (Eigen::Index i = 0; i < n; ++i) {
      const rumble::Footprint& f = footprints[static_cast<std::size_t>(i)];
      check_size(f, i);
      const auto soil =
          rumble::soils::equivalent_properties(layers_, half_space_, f.length, f.width);
      const auto footing = rumble::soils::surface_footing(soil, f.length, f.width);
      p.stiffness[i] = footing.stiffness;
      p.damping[i] = footing.dashpot;
      p.mass[i] = mass_.value_or(footing.mass);
    }
    return p;
  }

  void check_size(const rumble::Footprint& f, Eigen::Index i) const {
    if (f.length > 0.0 && f.width > 0.0 && std::isfinite(f.length * f.width)) return;
    std::ostringstream m;
    m << kTypeName << ": footprint " << i << " is " << f.length << " m x " << f.width
      << " m; deriving k, c, m from soil properties needs a length and width > 0";
    throw std::invalid_argument(m.str());
  }

  bool direct_;
  double stiffness_ = 0.0, damping_ = 0.0;  // N/m, N s/m (direct)
  std::optional<double> mass_;              // kg; default 0 (direct) or Wolf's (from soil)
  rumble::soils::SoilProperties half_space_;
  std::vector<rumble::soils::SoilLayer> layers_;
};

}  // namespace

RUMBLE_PLUGIN("winkler", "0.3.0", Winkler)
