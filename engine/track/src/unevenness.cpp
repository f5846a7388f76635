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

/// spec[key] as a number; `type` names the unevenness type for the message.
double number(const nlohmann::json& spec, const char* key, const std::string& type) {
  if (!spec.contains(key)) fail(key, "required for type '" + type + "'");
  const auto& v = spec.at(key);
  if (!v.is_number()) fail(key, "must be a number, got " + v.dump());
  return v.get<double>();
}

double positive(const nlohmann::json& spec, const char* key, const std::string& type) {
  const double v = number(spec, key, type);
  if (!(v > 0.0) || !std::isfinite(v)) fail(key, "must be > 0 m, got " + number_text(v));
  return v;
}

}  // namespace

Unevenness::Unevenness(const nlohmann::json& spec, const std::vector<double>& wheel_radii,
                       double x_min, double x_max) {
  if (!spec.is_object()) fail("", "must be an object, got " + spec.dump());
  const auto type_it = spec.find("type");
  const std::string type = type_it == spec.end()  ? "none"
                           : type_it->is_string() ? type_it->get<std::string>()
                                                  : "";
  if (type == "dip" || type == "bump") {
    read_shape(spec, type);
  } else if (type == "wheel_flat") {
    read_wheel_flat(spec, wheel_radii);
  } else if (type == "random") {
    read_random(spec, x_min, x_max);
  } else if (type != "none") {
    fail("type", "unknown type " + (type_it == spec.end() ? std::string("?") : type_it->dump()) +
                     "; use none, dip, bump, wheel_flat or random");
  }
}

void Unevenness::read_shape(const nlohmann::json& spec, const std::string& type) {
  kind_ = Kind::kShape;
  centre_ = number(spec, "position", type);
  if (!std::isfinite(centre_)) fail("position", "must be finite, got " + number_text(centre_));
  length_ = positive(spec, "length", type);
  amplitude_ = type == "dip" ? positive(spec, "depth", type) : -positive(spec, "height", type);
  wavenumber_ = 2.0 * std::numbers::pi / length_;
}

void Unevenness::read_wheel_flat(const nlohmann::json& spec,
                                 const std::vector<double>& wheel_radii) {
  const std::string type = "wheel_flat";
  kind_ = Kind::kWheelFlat;
  if (spec.contains("wheel")) {
    const auto& w = spec.at("wheel");
    if (!w.is_number_integer() || w.get<std::int64_t>() < 0)
      fail("wheel", "must be an integer >= 0, got " + w.dump());
    flat_wheel_ = w.get<std::size_t>();
  }
  if (flat_wheel_ >= wheel_radii.size()) {
    fail("wheel", "wheel " + std::to_string(flat_wheel_) + " does not exist; the vehicles have " +
                      std::to_string(wheel_radii.size()) + " wheel(s), numbered from 0");
  }
  const double radius = wheel_radii[flat_wheel_];
  if (!(radius > 0.0)) fail("wheel", "wheel radius must be > 0 m, got " + number_text(radius));
  circumference_ = 2.0 * std::numbers::pi * radius;
  length_ = positive(spec, "length", type);
  if (length_ >= circumference_) {
    fail("length", "a flat of " + number_text(length_) +
                       " m does not fit on a wheel of circumference " +
                       number_text(circumference_) + " m");
  }
  wavenumber_ = 2.0 * std::numbers::pi / length_;
  amplitude_ =
      spec.contains("depth") ? positive(spec, "depth", type) : length_ * length_ / (16.0 * radius);
  first_impact_ = std::numbers::pi * radius;
  if (spec.contains("first_impact")) {
    first_impact_ = number(spec, "first_impact", type);
    if (!(first_impact_ >= 0.0 && first_impact_ < circumference_)) {
      fail("first_impact", "must be in [0, 2 pi R) = [0, " + number_text(circumference_) +
                               ") m, got " + number_text(first_impact_));
    }
  }
}

void Unevenness::read_random(const nlohmann::json& spec, double x_min, double x_max) {
  const std::string type = "random";
  if (!spec.contains("class")) fail("class", "required for type 'random'");
  if (!spec.at("class").is_string())
    fail("class", "must be a string, got " + spec.at("class").dump());
  std::optional<RoughnessSpectrum> spectrum;
  try {
    spectrum = RoughnessSpectrum::from_name(spec.at("class").get<std::string>());
  } catch (const std::invalid_argument& e) {
    fail("class", e.what());
  }
  if (!spec.contains("seed")) fail("seed", "required for type 'random'");
  const auto& seed = spec.at("seed");
  if (!seed.is_number_unsigned() && !(seed.is_number_integer() && seed.get<std::int64_t>() >= 0)) {
    fail("seed", "must be an integer >= 0, got " + seed.dump());
  }
  const double lambda_min = positive(spec, "wavelength_min", type);
  const double lambda_max = positive(spec, "wavelength_max", type);
  if (!(lambda_max > lambda_min)) {
    fail("wavelength_max", "must be > wavelength_min = " + number_text(lambda_min) + " m, got " +
                               number_text(lambda_max) + " m");
  }
  try {
    random_.emplace(*spectrum, lambda_min, lambda_max, seed.get<std::uint64_t>(), x_min, x_max);
  } catch (const std::invalid_argument& e) {
    fail("", e.what());
  }
  kind_ = Kind::kRandom;
}

}  // namespace rumble
