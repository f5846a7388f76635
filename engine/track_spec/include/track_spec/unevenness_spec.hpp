// A scenario's /track/unevenness (docs/scenario.md) as plain numbers, read once from the
// validated object: the schema has checked every type and range and filled the defaults, so
// nothing here checks them again. The relations the schema cannot state are checked in one
// place, band_findings(), for validation (scenario/relation_checks) and the track alike.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace rumble {

struct UnevennessSpec {
  enum class Kind { kNone, kDip, kBump, kWheelFlat, kRandom };
  Kind kind = Kind::kNone;
  double position = 0.0;               // m: the centre of a dip or a bump
  double length = 0.0;                 // m: of a dip, a bump or a wheel flat
  double height = 0.0;                 // m: a dip's depth or a bump's height (both > 0)
  std::size_t wheel = 0;               // the flat wheel, among all wheels
  std::optional<double> flat_depth;    // m; absent: L^2 / (16 R), from the wheel's radius
  std::optional<double> first_impact;  // m; absent: pi R
  std::string spectrum;                // random: FRA1 .. FRA6, ISO3095 (unevenness_psd.hpp)
  std::uint64_t seed = 0;
  double wavelength_min = 0.0, wavelength_max = 0.0;  // m

  /// From a validated /track/unevenness with its defaults filled.
  static UnevennessSpec from_json(const nlohmann::json& unevenness);
};

/// A relation the schema cannot state, broken: the key under /track/unevenness, what is wrong
/// with the value, and the fix.
struct UnevennessFinding {
  std::string key;
  std::string message;
  std::string hint;
};

/// A random profile's band: ordered, and inside where its spectrum is defined (ISO 3095 covers
/// rail roughness only). Empty when it holds or the profile is not random.
std::vector<UnevennessFinding> band_findings(const UnevennessSpec& spec);

}  // namespace rumble
