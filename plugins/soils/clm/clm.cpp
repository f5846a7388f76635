// clm: the Coupled Lumped Mass soil (Kouroussis, Gazetas, Anastasopoulos, Conti, Verlinden,
// Soil Dyn. Earthq. Eng. 31(12), 2011): per footprint a mass m_f, spring k_f and dashpot c_f
// to the ground, and a spring k_c and dashpot c_c to each neighbour. Five parameters, given
// directly, or from soil properties by the static chain rule (physics.md §2.3 b, docs/soils.md):
//   G0 = compliance of one loaded footprint, r = neighbour / direct compliance ratio (both from
//   Boussinesq's solution for uniform pressure, averaged over the footprint), then
//   k_f = (1/G0)(1 - r)/(1 + r),  k_c = (1/G0) r/(1 - r^2)  (the chain reproduces G0 and r);
//   c_f, c_c = tau k_f, tau k_c with tau = C_z G0 (Lysmer's dashpot over the static stiffness);
//   m_f = Wolf's cone trapped mass (0 for nu <= 1/3), or given: fit it with `rumble calibrate`.
// A massless soil under explicit coupling closes an algebraic loop through the ballast and soil
// dashpots (docs/decisions/0004): give m_f when the soil is soft.
#include <cmath>
#include <rumble/params.hpp>
#include <rumble/plugin.hpp>
#include <sstream>
#include <string>

#include "half_space.hpp"
#include "lumped_soil.hpp"
#include "soil_properties_params.hpp"

namespace {

using rumble::soils::SoilProperties;

class Clm final : public rumble::soils::LumpedSoil {
 public:
  static constexpr const char* kTypeName = "clm";
  static constexpr const char* kSummary =
      "Coupled Lumped Mass soil (Kouroussis 2011): mass-spring-dashpot per footprint, coupled "
      "to its neighbours; direct or calibrated from soil properties";
  static const char* params_schema() {
    static const std::string schema = std::string(R"schema({
  "type": "object",
  "additionalProperties": false,
  "description": "give the five parameters m_f, k_f, c_f, k_c, c_c, or E, nu and rho (and optionally layers)",
  "oneOf": [{"required": ["m_f", "k_f", "c_f", "k_c", "c_c"]}, {"required": ["E", "nu", "rho"]}],
  "properties": {
    "m_f": {"type": "number", "minimum": 0, "description": "foundation mass per footprint [kg]; with soil properties it overrides Wolf's trapped mass (0 for nu <= 1/3)"},
    "k_f": {"type": "number", "exclusiveMinimum": 0, "description": "spring to the ground per footprint [N/m]"},
    "c_f": {"type": "number", "minimum": 0, "description": "dashpot to the ground per footprint [N s/m]"},
    "k_c": {"type": "number", "minimum": 0, "description": "coupling spring between neighbouring footprints [N/m]"},
    "c_c": {"type": "number", "minimum": 0, "description": "coupling dashpot between neighbouring footprints [N s/m]"},
    "max_step": {"type": "number", "exclusiveMinimum": 0, "description": "largest internal time step [s] (default: 1/20 of the shortest natural period, or a tenth of the relaxation time without mass)"},)schema") +
                                      rumble::soils::kSoilPropertiesSchema + R"schema(
  }
})schema";
    return schema.c_str();
  }

  Clm(const std::string& params_json, const rumble::Host& /*host*/) : p_(params_json) {
    if (p_.has("k_f") == p_.has("E")) {
      throw std::invalid_argument(
          "clm: give either the five parameters m_f, k_f, c_f, k_c, c_c or the soil properties "
          "E, nu, rho, not both or neither");
    }
    max_step_ = p_.get_or<double>("max_step", 0.0);
  }

 private:
  const char* name() const override { return kTypeName; }

  void configure(const std::vector<rumble::Footprint>& fp) override {
    check_chain(fp);
    double m = 0.0, k = 0.0, c = 0.0;
    if (p_.has("k_f")) {
      m = p_.get<double>("m_f");
      k = p_.get<double>("k_f");
      c = p_.get<double>("c_f");
      k_coupling_ = p_.get<double>("k_c");
      c_coupling_ = p_.get<double>("c_c");
    } else {
      const rumble::Footprint& f = fp.front();
      const double spacing = fp.size() > 1 ? fp[1].x - fp[0].x : 10.0 * f.length;
      const SoilProperties s =
          rumble::soils::equivalent_properties(p_, std::max(f.length, f.width));
      const double g0 = rumble::soils::flexible_mean_compliance(s, f.length, f.width, 0.0);
      const double r = rumble::soils::flexible_mean_compliance(s, f.length, f.width, spacing) / g0;
      k = (1.0 / g0) * (1.0 - r) / (1.0 + r);
      k_coupling_ = (1.0 / g0) * r / (1.0 - r * r);
      const double area = f.length * f.width;
      const double tau = rumble::soils::lysmer_dashpot(s, area) * g0;  // s
      c = tau * k;
      c_coupling_ = tau * k_coupling_;
      m = p_.has("m_f") ? p_.get<double>("m_f") : rumble::soils::wolf_trapped_mass(s, area);
    }
    std::fill(m_.begin(), m_.end(), m);
    std::fill(k_.begin(), k_.end(), k);
    std::fill(c_.begin(), c_.end(), c);
  }

  /// The chain couples footprint i to i +- 1 only: equal footprints, equally spaced on a line.
  void check_chain(const std::vector<rumble::Footprint>& fp) const {
    if (fp.size() < 2) return;
    const double spacing = fp[1].x - fp[0].x;
    for (std::size_t i = 0; i < fp.size(); ++i) {
      std::ostringstream m;
      const double expected = fp[0].x + static_cast<double>(i) * spacing;
      if (!(spacing > 0.0)) {
        m << "footprints must be ordered along the track with a positive spacing; footprint 1 "
             "is at x = "
          << fp[1].x << " m, footprint 0 at " << fp[0].x << " m";
      } else if (std::abs(fp[i].x - expected) > 1e-9 * spacing * static_cast<double>(fp.size())) {
        m << "footprints must be equally spaced along the track; footprint " << i
          << " is at x = " << fp[i].x << " m, expected " << expected << " m (spacing " << spacing
          << " m)";
      } else if (fp[i].y != fp[0].y || fp[i].length != fp[0].length || fp[i].width != fp[0].width) {
        m << "all footprints must be equal and on one line; footprint " << i
          << " differs from "
             "footprint 0 (y, length, width)";
      } else {
        continue;
      }
      throw std::invalid_argument("clm: " + m.str() +
                                  "; the chain couples neighbours only (use winkler otherwise)");
    }
  }

  rumble::Params p_;
};

}  // namespace

RUMBLE_PLUGIN("clm", "0.1.0", Clm)
