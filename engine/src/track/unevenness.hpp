// Rail and wheel unevenness: the profile r [m] (down +, a dip is positive) seen by each wheel,
// entering the contact as delta = z_wheel - w_rail - r. Built once from the scenario's
// track.unevenness; at() is O(1) and allocates nothing (it runs every micro-step per wheel).
//   none        smooth
//   dip, bump   cosine shape of the given length centred at `position`: a rail joint, a weld
//   wheel_flat  a flat of `length` on one wheel: a cosine dip of `depth` once per revolution,
//               first under the wheel after half a revolution (distance rolled pi R)
//   random      a stationary random profile from the US FRA PSD of a track class, generated
//               on a grid along the whole rail with a seeded generator and read by linear
//               interpolation
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <vector>

namespace rumble {

class Unevenness {
 public:
  /// spec: validated /track/unevenness. wheel_radii [m] of all wheels. The random profile
  /// covers [x_min, x_max] [m]. Throws std::invalid_argument on inconsistent input.
  Unevenness(const nlohmann::json& spec, const std::vector<double>& wheel_radii, double x_min,
             double x_max);

  /// Profile under wheel `wheel` at contact position x [m] after rolling `distance_rolled` [m].
  double at(std::size_t wheel, double x, double distance_rolled) const;

  /// One-sided PSD of an FRA class (1..6) [m^2 / (rad/m)] at spatial frequency omega [rad/m].
  static double fra_psd(int track_class, double omega);

 private:
  enum class Kind { kNone, kShape, kWheelFlat, kRandom };
  Kind kind_ = Kind::kNone;
  double centre_ = 0.0, length_ = 0.0, amplitude_ = 0.0;  // m; amplitude < 0 for a bump
  std::size_t flat_wheel_ = 0;
  double circumference_ = 0.0, first_impact_ = 0.0;  // m
  double x0_ = 0.0, dx_ = 1.0;                       // random profile grid [m]
  std::vector<double> profile_;                      // m
};

}  // namespace rumble
