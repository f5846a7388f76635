#include "track/unevenness.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/number_text.hpp"

namespace rumble {
namespace {

constexpr const char* kPointer = "/track/unevenness";

[[noreturn]] void fail(const std::string& key, const std::string& message) {
  throw std::invalid_argument(std::string(kPointer) + (key.empty() ? "" : "/" + key) + ": " +
                              message);
}

}  // namespace

Unevenness::Unevenness(const UnevennessSpec& spec, const std::vector<double>& wheel_radii,
                       double x_min, double x_max) {
  switch (spec.kind) {
    case UnevennessSpec::Kind::kNone:
      break;
    case UnevennessSpec::Kind::kDip:
    case UnevennessSpec::Kind::kBump:
      read_shape(spec);
      break;
    case UnevennessSpec::Kind::kWheelFlat:
      read_wheel_flat(spec, wheel_radii);
      break;
    case UnevennessSpec::Kind::kRandom:
      read_random(spec, x_min, x_max);
      break;
  }
}

void Unevenness::read_shape(const UnevennessSpec& spec) {
  kind_ = Kind::kShape;
  centre_ = spec.position;
  length_ = spec.length;
  amplitude_ = spec.kind == UnevennessSpec::Kind::kDip ? spec.height : -spec.height;
  wavenumber_ = 2.0 * std::numbers::pi / length_;
}

void Unevenness::read_wheel_flat(const UnevennessSpec& spec,
                                 const std::vector<double>& wheel_radii) {
  kind_ = Kind::kWheelFlat;
  flat_wheel_ = spec.wheel;
  if (flat_wheel_ >= wheel_radii.size()) {
    fail("wheel", "wheel " + std::to_string(flat_wheel_) + " does not exist; the vehicles have " +
                      std::to_string(wheel_radii.size()) + " wheel(s), numbered from 0");
  }
  const double radius = wheel_radii[flat_wheel_];
  if (!(radius > 0.0)) fail("wheel", "wheel radius must be > 0 m, got " + number_text(radius));
  circumference_ = 2.0 * std::numbers::pi * radius;
  length_ = spec.length;
  if (length_ >= circumference_) {
    fail("length", "a flat of " + number_text(length_) +
                       " m does not fit on a wheel of circumference " +
                       number_text(circumference_) + " m");
  }
  wavenumber_ = 2.0 * std::numbers::pi / length_;
  amplitude_ = spec.flat_depth.value_or(length_ * length_ / (16.0 * radius));
  first_impact_ = spec.first_impact.value_or(std::numbers::pi * radius);
  if (!(first_impact_ < circumference_)) {
    fail("first_impact", "must be in [0, 2 pi R) = [0, " + number_text(circumference_) +
                             ") m, got " + number_text(first_impact_));
  }
}

void Unevenness::read_random(const UnevennessSpec& spec, double x_min, double x_max) {
  if (const auto findings = band_findings(spec); !findings.empty())
    fail(findings.front().key, findings.front().message);
  try {
    random_.emplace(RoughnessSpectrum::from_name(spec.spectrum), spec.wavelength_min,
                    spec.wavelength_max, spec.seed, x_min, x_max);
  } catch (const std::invalid_argument& e) {
    fail("", e.what());
  }
  kind_ = Kind::kRandom;
}

}  // namespace rumble
