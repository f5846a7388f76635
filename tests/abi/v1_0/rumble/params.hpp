// SPDX-License-Identifier: MIT
// rumble/params.hpp: reading a component's params (JSON text) in a plugin. Optional header: it
// needs nlohmann-json (find_package(nlohmann_json) is done by the Rumble package config).
// The host has already validated params against the component's schema and filled every
// declared default, so a missing required key here is a plugin bug, reported as such.
#ifndef RUMBLE_PARAMS_HPP
#define RUMBLE_PARAMS_HPP

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

namespace rumble {

class Params {
 public:
  explicit Params(const std::string& json_text) : j_(nlohmann::json::parse(json_text)) {}
  bool has(const char* key) const { return j_.contains(key) && !j_.at(key).is_null(); }
  /// Required value; throws with the JSON pointer when absent or of the wrong type.
  template <class T>
  T get(const char* key) const {
    if (!has(key)) throw std::invalid_argument(std::string("params/") + key + ": missing");
    try {
      return j_.at(key).get<T>();
    } catch (const nlohmann::json::exception& e) {
      throw std::invalid_argument(std::string("params/") + key + ": " + e.what());
    }
  }
  template <class T>
  T get_or(const char* key, T fallback) const {
    return has(key) ? get<T>(key) : fallback;
  }
  const nlohmann::json& json() const { return j_; }

 private:
  nlohmann::json j_;
};

}  // namespace rumble

#endif  // RUMBLE_PARAMS_HPP
