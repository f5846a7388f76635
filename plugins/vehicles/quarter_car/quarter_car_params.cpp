#include "quarter_car_params.hpp"

#include <nlohmann/json.hpp>
#include <string>

#include "json_reader.hpp"

namespace rumble::vehicles {
namespace {

// Defaults, per wheel (see the header for the source).
constexpr double kWheelMass = 906.5;     // kg
constexpr double kBogieMass = 653.75;    // kg
constexpr double kPrimaryK = 1.2e6;      // N/m
constexpr double kPrimaryC = 4.0e3;      // N s/m
constexpr double kCarBodyMass = 4000.0;  // kg
constexpr double kSecondaryK = 215.0e3;  // N/m
constexpr double kSecondaryC = 10.0e3;   // N s/m
constexpr double kWheelRadius = 0.46;    // m
constexpr double kStaticLoad = 0.0;      // N

std::string num(double x) {
  return nlohmann::json(x).dump();
}

/// A number param's bounds (JSON number texts) and the reason for them, which its description
/// states: "<meaning> [unit]; [lo, hi] unit: <why>" (every number has a physical range,
/// docs/scenario.md "Limits").
struct Bounds {
  const char* lo;
  const char* hi;
  const char* why;
};

constexpr Bounds kMassBounds{"1", "1e5",
                             "a rail vehicle carries 0.5 to 15 t per wheel; 100 t is a whole "
                             "loaded wagon"};
constexpr Bounds kStiffnessBounds{"1e3", "1e10",
                                  "suspension springs are 1e5 to 2e6 N/m per wheel; 1e10 N/m is "
                                  "practically rigid"};
constexpr Bounds kDampingBounds{"0", "1e7", "suspension dampers are 1e3 to 5e4 N s/m per wheel"};

std::string number_param(const char* unit, const Bounds& b, double fallback, const char* meaning) {
  return std::string(R"({"type": "number", "minimum": )") + b.lo + R"(, "maximum": )" + b.hi +
         R"(, "default": )" + num(fallback) + R"(, "description": ")" + meaning + " [" + unit +
         "]; [" + b.lo + ", " + b.hi + "] " + unit + ": " + b.why + R"("})";
}

std::string spring_damper_properties(double k, double c) {
  return R"("k": )" + number_param("N/m", kStiffnessBounds, k, "stiffness") + R"(, "c": )" +
         number_param("N s/m", kDampingBounds, c, "viscous damping");
}

std::string make_schema() {
  return R"({
  "type": "object",
  "additionalProperties": false,
  "description": "quarter car, values per wheel: wheel mass, primary spring-damper, bogie mass, optional secondary spring-damper and car-body mass. DOFs (down +): wheel, bogie[, car body] [m]",
  "properties": {
    "wheel_mass": )" +
         number_param("kg", kMassBounds, kWheelMass, "unsprung mass per wheel (half a wheelset)") +
         R"(,
    "bogie_mass": )" +
         number_param("kg", kMassBounds, kBogieMass,
                      "bogie mass carried by this wheel's primary suspension") +
         R"(,
    "primary": {"type": "object", "additionalProperties": false,
                "description": "primary suspension per wheel, wheel to bogie",
                "default": {"k": )" +
         num(kPrimaryK) + R"(, "c": )" + num(kPrimaryC) + R"(},
                "properties": {)" +
         spring_damper_properties(kPrimaryK, kPrimaryC) + R"(}},
    "secondary": {"type": "object", "additionalProperties": false,
                  "description": "optional secondary stage per wheel (bogie to car body); absent: two masses only",
                  "properties": {"car_body_mass": )" +
         number_param("kg", kMassBounds, kCarBodyMass, "car-body mass carried by this wheel") +
         ", " + spring_damper_properties(kSecondaryK, kSecondaryC) + R"(}},
    "static_load": )" +
         number_param("N",
                      {"0", "1e6",
                       "wheel loads are 50 to 125 kN (heavy haul, 40 t axles, about "
                       "200 kN)"},
                      kStaticLoad,
                      "constant downward load on the top mass (payload not modelled as a body)") +
         R"(,
    "wheel_radius": )" +
         number_param("m",
                      {"0.1", "2",
                       "from small tram and bogie wheels (0.3 m) to the largest "
                       "steam locomotive drivers (about 1.1 m)"},
                      kWheelRadius, "rolling radius") +
         R"(,
    "gravity": )" +
         number_param("m/s^2", {"0", "30", "9.81 on Earth, 0 switches gravity off"},
                      kStandardGravity, "gravitational acceleration") +
         R"(
  }
})";
}

SpringDamper read_spring_damper(ObjectReader& r, double k, double c) {
  SpringDamper s;
  s.k = r.positive_or("k", k, "N/m", "give the stiffness in N/m");
  s.c = r.non_negative_or("c", c, "N s/m", "give the damping in N s/m (0 for none)");
  return s;
}

}  // namespace

const char* quarter_car_schema() {
  static const std::string schema = make_schema();
  return schema.c_str();
}

QuarterCarParams parse_quarter_car_params(const std::string& params_json) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(params_json);
  } catch (const nlohmann::json::parse_error& e) {
    fail("params", std::string("not valid JSON: ") + e.what());
  }
  ObjectReader r(j, "params");
  QuarterCarParams p;
  constexpr const char* kMassFix = "give a positive mass in kg (per wheel)";
  p.wheel_mass = r.positive_or("wheel_mass", kWheelMass, "kg", kMassFix);
  p.bogie_mass = r.positive_or("bogie_mass", kBogieMass, "kg", kMassFix);
  if (const nlohmann::json* primary = r.value("primary")) {
    ObjectReader pr(*primary, r.at("primary"));
    p.primary = read_spring_damper(pr, kPrimaryK, kPrimaryC);
    pr.finish();
  } else {
    p.primary = {kPrimaryK, kPrimaryC};
  }
  if (const nlohmann::json* secondary = r.value("secondary")) {
    ObjectReader sr(*secondary, r.at("secondary"));
    SecondaryStage s;
    s.car_body_mass = sr.positive_or("car_body_mass", kCarBodyMass, "kg", kMassFix);
    s.suspension = read_spring_damper(sr, kSecondaryK, kSecondaryC);
    sr.finish();
    p.secondary = s;
  }
  p.static_load = r.non_negative_or("static_load", kStaticLoad, "N", "give the load in N");
  p.wheel_radius = r.positive_or("wheel_radius", kWheelRadius, "m", "give the rolling radius in m");
  p.gravity = r.non_negative_or("gravity", kStandardGravity, "m/s^2",
                                "9.81 on Earth, 0 to switch gravity off");
  r.finish();
  return p;
}

}  // namespace rumble::vehicles
