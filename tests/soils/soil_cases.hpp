// The seed's three soils (docs/physics.md §1.4: E = 10, 155, 750 MPa; nu = 0.3 and
// rho = 1800 kg/m^3 assumed there) and helpers to write a soil's params.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <string>

namespace rumble::test {

struct Soil {
  const char* name;
  double E;    // Pa
  double nu;   // -
  double rho;  // kg/m^3
};

inline constexpr std::array<Soil, 3> kSoils = {Soil{"soft", 10e6, 0.3, 1800.0},
                                               Soil{"medium", 155e6, 0.3, 1800.0},
                                               Soil{"stiff", 750e6, 0.3, 1800.0}};

/// {"E": .., "nu": .., "rho": ..}
inline nlohmann::json soil_params(const Soil& s) {
  return {{"E", s.E}, {"nu", s.nu}, {"rho", s.rho}};
}

}  // namespace rumble::test
