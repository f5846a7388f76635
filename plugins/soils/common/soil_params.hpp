// Reading a reduced soil's params: the two ways of giving them (directly, or from soil
// properties), range checks with messages that name the key, the value and the rule, and the
// JSON Schema fragments both soils share. The host has validated the params against the schema
// already. The checks here are the model's own domain, not the schema's ranges: a value a direct
// caller of the C API could still give that would break the formulas (nu >= 0.5 divides by zero,
// k <= 0 has no motion), and what the schema cannot say (a direct key mixed with a soil key).
#pragma once

#include <cmath>
#include <initializer_list>
#include <rumble/params.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "half_space.hpp"
#include "layered_soil.hpp"

namespace rumble::soils {

/// Schema properties E, nu, rho and layers of a soil given by its properties (a fragment: the
/// text between the braces of "properties", without the closing brace); layers_description
/// says what the soil makes of the layers, extra_layer_properties (",\n" then properties) adds
/// properties of its own to each layer.
inline std::string soil_properties_schema(const std::string& layers_description,
                                          const std::string& extra_layer_properties = "") {
  return R"schema(
    "E": {"type": "number", "minimum": 1e5, "maximum": 1e12, "description": "Young's modulus of the half-space, below any layers [Pa]; with nu and rho it gives G = E / (2 (1 + nu)) [Pa] and c_s = sqrt(G / rho) [m/s], from which every parameter is derived; [1e5, 1e12] Pa: from peat (about 0.1 MPa) to hard rock (about 100 GPa)"},
    "nu": {"type": "number", "minimum": 0, "maximum": 0.495, "description": "Poisson ratio of the half-space [-]; [0, 0.495]: soils are 0.2 to 0.4 dry, water-saturated clay about 0.49; nearer 0.5 the soil is incompressible and c_p = c_s sqrt((2 - 2 nu) / (1 - 2 nu)) grows without bound (a FEM soil's explicit step with it)"},
    "rho": {"type": "number", "minimum": 500, "maximum": 5000, "description": "density of the half-space [kg/m^3]; [500, 5000] kg/m^3: from peat (about 1000) to dense rock (about 3000)"},
    "layers": {
      "type": "array",
      "description": ")schema" +
         layers_description + R"schema(",
      "items": {
        "type": "object",
        "additionalProperties": false,
        "required": ["thickness", "E", "nu", "rho"],
        "properties": {
          "thickness": {"type": "number", "minimum": 0.05, "maximum": 1000, "description": "layer thickness [m]; [0.05, 1000] m: from a thin asphalt or blinding layer (some cm) to far deeper than a train's waves reach (some 10 m)"},
          "E": {"type": "number", "minimum": 1e5, "maximum": 1e12, "description": "Young's modulus of the layer [Pa]; [1e5, 1e12] Pa: from peat (about 0.1 MPa) to hard rock (about 100 GPa)"},
          "nu": {"type": "number", "minimum": 0, "maximum": 0.495, "description": "Poisson ratio of the layer [-]; [0, 0.495]: soils are 0.2 to 0.4 dry, water-saturated clay about 0.49; nearer 0.5 the soil is incompressible and c_p = c_s sqrt((2 - 2 nu) / (1 - 2 nu)) grows without bound (a FEM soil's explicit step with it)"},
          "rho": {"type": "number", "minimum": 500, "maximum": 5000, "description": "density of the layer [kg/m^3]; [500, 5000] kg/m^3: from peat (about 1000) to dense rock (about 3000)"})schema" +
         extra_layer_properties + R"schema(
        }
      }
    })schema";
}

/// The reduced soils' fragment: layers become one equivalent soil per footprint.
inline const std::string kSoilPropertiesSchema = soil_properties_schema(
    "layers over the half-space, top first; replaced per footprint by one equivalent soil: "
    "1/E_eq = sum w_j / E_j, nu and rho averaged with w_j, w_j the share of the layer in the "
    "integral over depth of the Boussinesq vertical stress under the footprint centre "
    "(layer-summation settlement; docs/soils.md)");

/// Schema property of the internal time step, shared by the reduced soils.
inline constexpr const char* kMaxStepSchema = R"schema(
    "max_step": {"type": "number", "minimum": 1e-7, "maximum": 1, "description": "longest internal sub-step [s]; each macro step H is cut into equal sub-steps no longer than this (default: 1/20 of the period of the fastest free motion, from the parameters; docs/soils.md); [1e-7, 1] s: as time.macro_step's (the soil's fastest motion is some 100 Hz; a sub-step of 1e-7 s is far finer than it needs)"})schema";

class SoilParams {
 public:
  /// type_name prefixes every message ("winkler: params/k: ...").
  SoilParams(const std::string& json_text, std::string type_name)
      : p_(json_text), type_(std::move(type_name)) {}

  bool has(const char* key) const { return p_.has(key); }

  /// True for the direct parameters, false for soil properties. Throws when the params give
  /// keys of both sets or of neither, naming them.
  bool direct(std::initializer_list<const char*> direct_keys, const char* direct_text) const {
    std::vector<std::string> given_direct, given_soil;
    for (const char* k : direct_keys)
      if (p_.has(k)) given_direct.emplace_back(k);
    for (const char* k : {"E", "nu", "rho", "layers"})
      if (p_.has(k)) given_soil.emplace_back(k);
    if (!given_direct.empty() && given_soil.empty()) return true;
    if (given_direct.empty() && !given_soil.empty()) return false;
    std::string m = type_ + ": give either " + direct_text +
                    " (direct), or E, nu and rho (from soil properties)";
    if (given_direct.empty()) throw std::invalid_argument(m + "; got neither");
    throw std::invalid_argument(m + ", not both; got " + list(given_direct) + " with " +
                                list(given_soil));
  }

  /// Required number > 0 (positive) or >= 0 ([unit] for the message).
  double positive(const char* key, const char* unit) const { return number(key, unit, true); }
  double non_negative(const char* key, const char* unit) const { return number(key, unit, false); }
  double non_negative_or(const char* key, const char* unit, double fallback) const {
    return p_.has(key) ? number(key, unit, false) : fallback;
  }

  /// The half-space (E, nu, rho), checked.
  SoilProperties half_space() const {
    const SoilProperties s{required("E"), required("nu"), required("rho")};
    check_properties(s, type_ + ": params");
    return s;
  }

  /// The layers (empty when not given), checked.
  std::vector<SoilLayer> layers() const {
    std::vector<SoilLayer> out;
    if (!p_.has("layers")) return out;
    const auto& layers = p_.json().at("layers");
    for (std::size_t i = 0; i < layers.size(); ++i) {
      const std::string where = type_ + ": params/layers/" + std::to_string(i);
      const auto value = [&](const char* key) { return layer_value(layers[i], where, key); };
      SoilLayer layer{value("thickness"), {value("E"), value("nu"), value("rho")}};
      if (!(layer.thickness > 0.0) || !std::isfinite(layer.thickness)) {
        std::ostringstream m;
        m << where << "/thickness: must be > 0 m, got " << layer.thickness;
        throw std::invalid_argument(m.str());
      }
      check_properties(layer.properties, where);
      out.push_back(layer);
    }
    return out;
  }

  const std::string& type_name() const { return type_; }

 private:
  double required(const char* key) const {
    if (!p_.has(key)) throw std::invalid_argument(type_ + ": params/" + key + ": missing");
    return p_.get<double>(key);
  }

  double number(const char* key, const char* unit, bool strictly) const {
    const double x = required(key);
    if ((strictly ? x > 0.0 : x >= 0.0) && std::isfinite(x)) return x;
    std::ostringstream m;
    m << type_ << ": params/" << key << ": must be " << (strictly ? "> 0 " : ">= 0 ") << unit
      << ", got " << x;
    throw std::invalid_argument(m.str());
  }

  // A layer's number `key` (the schema requires each of a layer's four).
  static double layer_value(const nlohmann::json& layer, const std::string& where,
                            const char* key) {
    const auto it = layer.find(key);
    if (it == layer.end() || !it->is_number())
      throw std::invalid_argument(where + "/" + key + ": missing or not a number");
    return it->get<double>();
  }

  static std::string list(const std::vector<std::string>& keys) {
    std::string s;
    for (std::size_t i = 0; i < keys.size(); ++i)
      s += (i == 0 ? "" : (i + 1 == keys.size() ? " and " : ", ")) + keys[i];
    return s;
  }

  rumble::Params p_;
  std::string type_;
};

}  // namespace rumble::soils
