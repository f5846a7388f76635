// winkler: one spring-dashpot (and optional participating mass) per footprint, no coupling.
// Given directly (k, c, m) or from soil properties and the footprint geometry: Gazetas (1991)
// static stiffness of a rigid rectangle, Lysmer's analog radiation dashpot, Wolf's cone
// trapped mass (docs/soils.md).
#include <rumble/params.hpp>
#include <rumble/plugin.hpp>
#include <string>

#include "half_space.hpp"
#include "lumped_soil.hpp"
#include "soil_properties_params.hpp"

namespace {

using rumble::soils::SoilProperties;

class Winkler final : public rumble::soils::LumpedSoil {
 public:
  static constexpr const char* kTypeName = "winkler";
  static constexpr const char* kSummary =
      "one spring-dashpot (+ optional mass) per footprint; direct or from soil properties "
      "(Gazetas stiffness, Lysmer dashpot)";
  static const char* params_schema() {
    static const std::string schema = std::string(R"schema({
  "type": "object",
  "additionalProperties": false,
  "description": "give k and c (and optionally m), or E, nu and rho (and optionally layers)",
  "oneOf": [{"required": ["k", "c"]}, {"required": ["E", "nu", "rho"]}],
  "properties": {
    "k": {"type": "number", "exclusiveMinimum": 0, "description": "spring per footprint [N/m]"},
    "c": {"type": "number", "minimum": 0, "description": "dashpot per footprint [N s/m]"},
    "m": {"type": "number", "minimum": 0, "description": "participating mass per footprint [kg] (default 0; from soil: Wolf's cone trapped mass, non-zero for nu > 1/3)"},
    "max_step": {"type": "number", "exclusiveMinimum": 0, "description": "largest internal time step [s] (default: 1/20 of the natural period, or c/(10 k) without mass)"},)schema") +
                                      rumble::soils::kSoilPropertiesSchema + R"schema(
  }
})schema";
    return schema.c_str();
  }

  Winkler(const std::string& params_json, const rumble::Host& /*host*/) : p_(params_json) {
    if (p_.has("k") == p_.has("E")) {
      throw std::invalid_argument(
          "winkler: give either k and c (direct) or E, nu and rho (from soil properties), not "
          "both or neither");
    }
    max_step_ = p_.get_or<double>("max_step", 0.0);
  }

 private:
  const char* name() const override { return kTypeName; }

  void configure(const std::vector<rumble::Footprint>& footprints) override {
    for (std::size_t i = 0; i < footprints.size(); ++i) {
      if (p_.has("k")) {
        k_[i] = p_.get<double>("k");
        c_[i] = p_.get<double>("c");
        m_[i] = p_.get_or<double>("m", 0.0);
        continue;
      }
      const rumble::Footprint& f = footprints[i];
      const SoilProperties s =
          rumble::soils::equivalent_properties(p_, std::max(f.length, f.width));
      const double area = f.length * f.width;
      k_[i] = rumble::soils::gazetas_vertical_stiffness(s, f.length, f.width);
      c_[i] = rumble::soils::lysmer_dashpot(s, area);
      m_[i] = p_.has("m") ? p_.get<double>("m") : rumble::soils::wolf_trapped_mass(s, area);
    }
  }

  rumble::Params p_;
};

}  // namespace

RUMBLE_PLUGIN("winkler", "0.1.0", Winkler)
