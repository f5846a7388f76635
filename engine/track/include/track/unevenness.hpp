// Rail and wheel unevenness: the profile r [m] (down +, a dip is positive) seen by each wheel,
// entering the contact as delta = z_wheel - w_rail(x_c) - r. Built once from the scenario's
// track.unevenness (docs/scenario.md); at() is O(1) and allocates nothing (it runs every
// micro-step for every wheel).
//   none        r = 0.
//   dip, bump   raised cosine of `length` L centred at `position` x_p (a rail joint, a weld):
//               r = h (1 - cos(2 pi (x - x0) / L)) / 2 for x0 = x_p - L/2 <= x <= x0 + L,
//               0 elsewhere; h = depth (dip) or -height (bump). C1 at both ends.
//   wheel_flat  a rounded flat of `length` L on wheel `wheel` (default 0), radius R: a raised
//               cosine of length L and depth d in the rolled distance, repeating every 2 pi R
//               of rolled distance. d defaults to L^2 / (16 R), the rounded (worn) flat of
//               length L (a fresh flat of chord l has the depth l^2 / (8 R); worn to a rounded
//               flat of the same depth it is sqrt(2) l long: Wu & Thompson, J. Sound Vib. 251,
//               2002; Johansson & Nielsen, Proc. IMechE F 217, 2003).
//               Phase: the flat's centre is under the contact when the rolled distance is
//               first_impact + n 2 pi R; `first_impact` [m] defaults to pi R (half a turn),
//               so a flat shorter than the circumference is off the rail at the start.
//               Other wheels see r = 0; the position x plays no part.
//   random      a random rail profile of PSD `class` (FRA1 .. FRA6, ISO3095; see
//               unevenness_psd.hpp for the spectra and their units) in the band
//               [wavelength_min, wavelength_max] with the given `seed`, synthesized once over
//               the track span (unevenness_random.hpp); the same for every wheel.
#pragma once

#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "track/unevenness_random.hpp"
#include "track_spec/unevenness_spec.hpp"

namespace rumble {

class Unevenness {
 public:
  /// spec: /track/unevenness as validated (track_spec/unevenness_spec.hpp). wheel_radii [m] of
  /// all wheels, in the order the track numbers them. The random profile covers
  /// [x_min, x_max] [m] without repeating. Throws std::invalid_argument with the key's JSON
  /// pointer when a relation the schema cannot check fails: a flat wheel that does not exist or
  /// a flat that does not fit on it, a band outside its spectrum, a span too long to synthesize.
  Unevenness(const UnevennessSpec& spec, const std::vector<double>& wheel_radii, double x_min,
             double x_max);

  /// Profile [m, down +] under wheel `wheel` at contact position x [m] after the wheel has
  /// rolled `distance_rolled` [m].
  double at(std::size_t wheel, double x, double distance_rolled) const noexcept {
    switch (kind_) {
      case Kind::kNone:
        return 0.0;
      case Kind::kShape:
        return amplitude_ * raised_cosine(x - centre_);
      case Kind::kWheelFlat: {
        if (wheel != flat_wheel_) return 0.0;
        // Distance rolled from the nearest passage of the flat's centre over the rail.
        const double s = distance_rolled - first_impact_;
        return amplitude_ * raised_cosine(s - circumference_ * std::round(s / circumference_));
      }
      case Kind::kRandom:
        return random_->at(x);
    }
    return 0.0;
  }

 private:
  enum class Kind { kNone, kShape, kWheelFlat, kRandom };

  // The constructor's reading of each type: a dip or a bump, a wheel flat, a random profile.
  void read_shape(const UnevennessSpec& spec);
  void read_wheel_flat(const UnevennessSpec& spec, const std::vector<double>& wheel_radii);
  void read_random(const UnevennessSpec& spec, double x_min, double x_max);

  /// (1 + cos(2 pi s / L)) / 2 for |s| < L/2, else 0: 1 at the centre s = 0.
  double raised_cosine(double s) const noexcept {
    return std::abs(s) >= 0.5 * length_ ? 0.0 : 0.5 * (1.0 + std::cos(wavenumber_ * s));
  }

  Kind kind_ = Kind::kNone;
  double centre_ = 0.0, length_ = 0.0, wavenumber_ = 0.0;  // m, m, rad/m (2 pi / L)
  double amplitude_ = 0.0;                                 // m; < 0 for a bump
  std::size_t flat_wheel_ = 0;
  double circumference_ = 1.0, first_impact_ = 0.0;  // m
  std::optional<RandomProfile> random_;
};

}  // namespace rumble
