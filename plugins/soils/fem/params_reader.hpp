// One object of the FEM soil's params, read after the host has validated them against the schema
// and filled every default it declares (fem_schema.cpp): a key with a default is required here,
// so its absence names the key and the caller's bug instead of falling back on a second copy of
// the default. Messages start "fem: params/<key>: ".
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace rumble::fem {

class ParamsObject {
 public:
  /// `where`: the object's place below params, "" for params itself, "mesh/" for params/mesh.
  ParamsObject(const nlohmann::json& object, std::string where)
      : object_(object), where_(std::move(where)) {}

  /// The object `key` (every object of the schema has the default {}).
  ParamsObject object(const char* key) const { return {at(key), where_ + key + "/"}; }

  /// A key the schema gives a default (or requires).
  template <class T>
  T get(const char* key) const {
    try {
      return at(key).get<T>();
    } catch (const nlohmann::json::exception& e) {
      throw std::invalid_argument(prefix(key) + e.what());
    }
  }

  /// A key without a default in the schema: its default derives from other settings, which the
  /// caller says where it reads it.
  template <class T>
  std::optional<T> optional(const char* key) const {
    if (!object_.contains(key)) return std::nullopt;
    return get<T>(key);
  }

  /// "fem: params/mesh/radius: "
  std::string prefix(const char* key) const { return "fem: params/" + where_ + key + ": "; }

 private:
  const nlohmann::json& at(const char* key) const {
    const auto it = object_.find(key);
    if (it == object_.end() || it->is_null())
      throw std::invalid_argument(prefix(key) +
                                  "missing: the host fills in every default of the params schema "
                                  "before the soil reads them; a caller of the C API must too");
    return *it;
  }

  const nlohmann::json& object_;
  std::string where_;
};

}  // namespace rumble::fem
