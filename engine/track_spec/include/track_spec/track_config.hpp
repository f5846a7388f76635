// The track section of a scenario, as plain numbers (SI units, per rail; see docs/scenario.md).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>

#include "track_spec/unevenness_spec.hpp"

namespace rumble {

struct TrackConfig {
  // Sleepers (per rail seat) and their footprints on the soil (whole sleeper).
  int sleeper_count = 0;
  double sleeper_spacing = 0.0;   // m
  double sleeper_mass = 0.0;      // kg
  double footprint_length = 0.0;  // m, across the track
  double footprint_width = 0.0;   // m, along the track
  // Rail: Euler-Bernoulli beam.
  double rail_E = 0.0;                // Pa
  double rail_I = 0.0;                // m^4
  double rail_mass_per_length = 0.0;  // kg/m
  int elements_per_bay = 0;
  int overhang_bays = 0;
  double rayleigh_alpha = 0.0;  // 1/s, rail only
  double rayleigh_beta = 0.0;   // s, rail only
  // Railpad (rail node -> sleeper) and ballast (sleeper -> footprint), per rail seat.
  double pad_k = 0.0;      // N/m
  double pad_c = 0.0;      // N s/m
  double ballast_k = 0.0;  // N/m
  double ballast_c = 0.0;  // N s/m
  // Wheel/rail contact.
  std::optional<double> hertz_constant;  // N/m^1.5
  double rail_radius = 0.0;              // m
  double contact_E = 0.0;                // Pa
  double contact_nu = 0.0;
  // Integrator.
  std::optional<double> micro_step;  // s
  double newmark_gamma = 0.0;
  UnevennessSpec unevenness;

  /// From a scenario's /track object with its defaults filled: by validation, or for a track
  /// written by hand by scenario::track_with_defaults(). The defaults are declared once, in the
  /// scenario schema; a key missing here is a bug, reported by nlohmann's out_of_range.
  static TrackConfig from_json(const nlohmann::json& track);

  double bay_length() const { return sleeper_spacing; }
  double element_length() const { return sleeper_spacing / elements_per_bay; }
  int element_count() const { return (sleeper_count - 1 + 2 * overhang_bays) * elements_per_bay; }
  double rail_start() const { return -overhang_bays * sleeper_spacing; }  // m
  double rail_end() const { return rail_start() + element_count() * element_length(); }
  double sleeper_x(int i) const { return i * sleeper_spacing; }
  /// x [m] of the middle of the sleepers: where distance receivers stand.
  double middle_x() const { return 0.5 * (sleeper_count - 1) * sleeper_spacing; }
};

}  // namespace rumble
