// quarter_car_params.hpp: the parameters of the quarter_car vehicle, their schema and defaults.
// All values are per wheel (one wheel of one rail): the bogie and car-body masses are the shares
// carried by that wheel. Defaults: the Manchester benchmark passenger vehicle (Iwnicki 1998) cut
// into eighths: wheelset 1813 kg / 2, bogie 2615 kg / 4, car body 32 t / 8, primary 1.2 MN/m and
// 4 kN s/m per axle box, secondary 430 kN/m and 20 kN s/m per bogie side, halved per wheel.
#ifndef RUMBLE_QUARTER_CAR_PARAMS_HPP
#define RUMBLE_QUARTER_CAR_PARAMS_HPP

#include <optional>
#include <string>

namespace rumble::vehicles {

struct SpringDamper {
  double k = 0.0;  // N/m
  double c = 0.0;  // N s/m
};

struct SecondaryStage {
  double car_body_mass = 0.0;  // kg
  SpringDamper suspension;     // between bogie and car body
};

struct QuarterCarParams {
  double wheel_mass = 0.0;  // kg, unsprung
  double bogie_mass = 0.0;  // kg, on the primary suspension
  SpringDamper primary;     // between wheel and bogie
  std::optional<SecondaryStage> secondary;
  double static_load = 0.0;   // N, constant downward force on the top mass
  double wheel_radius = 0.0;  // m
  double gravity = 0.0;       // m/s^2
};

/// JSON Schema (draft 7) of the params, defaults included.
const char* quarter_car_schema();

/// Reads and checks the params (the host's schema check is not relied upon); throws
/// std::invalid_argument naming the pointer, value and fix.
QuarterCarParams parse_quarter_car_params(const std::string& params_json);

}  // namespace rumble::vehicles

#endif  // RUMBLE_QUARTER_CAR_PARAMS_HPP
