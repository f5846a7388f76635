#include "track/unevenness.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

namespace rumble {
namespace {

constexpr double kPi = std::numbers::pi;

/// Raised cosine of unit height and length L centred on 0: 1 at s = 0, 0 for |s| >= L/2.
double raised_cosine(double s, double L) {
  return std::abs(s) >= 0.5 * L ? 0.0 : 0.5 * (1.0 + std::cos(2.0 * kPi * s / L));
}

// US FRA track classes, vertical profile (as tabulated e.g. by Zhai, Vehicle-Track Coupled
// Dynamics, 2020, after the FRA's 1970s track-geometry surveys): A_v [cm^2 rad/m], and the
// cut-off Omega_c = 0.8245 rad/m common to all classes; k = 0.25.
constexpr double kFraAv[6] = {1.2107, 1.0181, 0.6816, 0.5376, 0.2095, 0.0339};
constexpr double kFraOmegaC = 0.8245;  // rad/m
constexpr double kFraK = 0.25;
// Random phases: components per decade of wavelength; enough that the profile's variance is
// within 1 % of the PSD's integral and its spectrum has no visible lines at the grid spacing.
constexpr int kComponentsPerDecade = 400;

}  // namespace

double Unevenness::fra_psd(int track_class, double omega) {
  if (track_class < 1 || track_class > 6) {
    throw std::invalid_argument("FRA track class must be 1..6, got " + std::to_string(track_class));
  }
  const double av = kFraAv[track_class - 1] * 1e-4;  // cm^2 -> m^2
  const double wc2 = kFraOmegaC * kFraOmegaC;
  return kFraK * av * wc2 / (omega * omega * (omega * omega + wc2));
}

Unevenness::Unevenness(const nlohmann::json& spec, const std::vector<double>& wheel_radii,
                       double x_min, double x_max) {
  const std::string type = spec.value("type", "none");
  if (type == "none") return;
  if (type == "dip" || type == "bump") {
    kind_ = Kind::kShape;
    centre_ = spec.at("position").get<double>();
    length_ = spec.at("length").get<double>();
    amplitude_ = type == "dip" ? spec.at("depth").get<double>() : -spec.at("height").get<double>();
    return;
  }
  if (type == "wheel_flat") {
    kind_ = Kind::kWheelFlat;
    flat_wheel_ = spec.value("wheel", std::size_t{0});
    if (flat_wheel_ >= wheel_radii.size()) {
      throw std::invalid_argument("/track/unevenness/wheel: wheel " + std::to_string(flat_wheel_) +
                                  " does not exist; the vehicles have " +
                                  std::to_string(wheel_radii.size()) +
                                  " wheel(s), numbered from 0");
    }
    const double radius = wheel_radii[flat_wheel_];
    length_ = spec.at("length").get<double>();
    amplitude_ = spec.at("depth").get<double>();
    circumference_ = 2.0 * kPi * radius;
    first_impact_ = kPi * radius;
    if (length_ >= circumference_) {
      throw std::invalid_argument("/track/unevenness/length: a flat of " + std::to_string(length_) +
                                  " m is longer than the wheel's circumference " +
                                  std::to_string(circumference_) + " m");
    }
    return;
  }
  if (type == "random") {
    const std::string cls = spec.at("class").get<std::string>();
    if (cls.rfind("FRA", 0) != 0 || cls.size() != 4 || cls[3] < '1' || cls[3] > '6') {
      throw std::invalid_argument("/track/unevenness/class: '" + cls +
                                  "' has no PSD in this version; use FRA1 .. FRA6");
    }
    const int track_class = cls[3] - '0';
    const double lambda_min = spec.at("wavelength_min").get<double>();
    const double lambda_max = spec.at("wavelength_max").get<double>();
    if (!(lambda_max > lambda_min)) {
      throw std::invalid_argument("/track/unevenness/wavelength_max: must be > wavelength_min (" +
                                  std::to_string(lambda_min) + " m), got " +
                                  std::to_string(lambda_max) + " m");
    }
    kind_ = Kind::kRandom;
    // Grid: 10 points per shortest wavelength, so linear interpolation is within 5 % there.
    dx_ = lambda_min / 10.0;
    x0_ = x_min;
    const auto n = static_cast<std::size_t>(std::ceil((x_max - x_min) / dx_)) + 2;
    profile_.assign(n, 0.0);
    // Sum of cosines with log-spaced spatial frequencies and uniform random phases:
    //   r(x) = sum_k sqrt(2 S(Omega_k) dOmega_k) cos(Omega_k x + phi_k),
    // whose variance is sum_k S dOmega ~ the integral of the one-sided PSD over the band.
    const double w_lo = 2.0 * kPi / lambda_max, w_hi = 2.0 * kPi / lambda_min;
    const auto m = static_cast<int>(std::ceil(kComponentsPerDecade * std::log10(w_hi / w_lo)));
    std::mt19937_64 rng(spec.at("seed").get<std::uint64_t>());
    std::uniform_real_distribution<double> phase(0.0, 2.0 * kPi);
    const double step = std::log(w_hi / w_lo) / m;
    for (int k = 0; k < m; ++k) {
      const double wa = w_lo * std::exp(step * k), wb = w_lo * std::exp(step * (k + 1));
      const double w = std::sqrt(wa * wb);
      const double amplitude = std::sqrt(2.0 * fra_psd(track_class, w) * (wb - wa));
      const double phi = phase(rng);
      for (std::size_t i = 0; i < n; ++i)
        profile_[i] += amplitude * std::cos(w * (x0_ + static_cast<double>(i) * dx_) + phi);
    }
    return;
  }
  throw std::invalid_argument("/track/unevenness/type: unknown type '" + type + "'");
}

double Unevenness::at(std::size_t wheel, double x, double distance_rolled) const {
  switch (kind_) {
    case Kind::kNone:
      return 0.0;
    case Kind::kShape:
      return amplitude_ * raised_cosine(x - centre_, length_);
    case Kind::kWheelFlat: {
      if (wheel != flat_wheel_) return 0.0;
      // Distance to the nearest passage of the flat's centre over the rail.
      const double s = distance_rolled - first_impact_;
      const double wrapped = s - circumference_ * std::round(s / circumference_);
      return amplitude_ * raised_cosine(wrapped, length_);
    }
    case Kind::kRandom: {
      const double s = (x - x0_) / dx_;
      const auto i = static_cast<std::size_t>(std::clamp(s, 0.0, double(profile_.size() - 2)));
      const double f = std::clamp(s - static_cast<double>(i), 0.0, 1.0);
      return (1.0 - f) * profile_[i] + f * profile_[i + 1];
    }
  }
  return 0.0;
}

}  // namespace rumble
