// json_reader.hpp: checked reading of vehicle parameters with messages a user can act on.
//
// Shared by the vehicle plugins (header-only, SDK + nlohmann-json only). The host validates a
// component's params against its JSON Schema, but a plugin must not rely on it: a definition file
// named by a param is never seen by the host, and tests create instances without a host. Every
// error names the place as a JSON pointer relative to the params ("params/bodies/2/mass") or to
// the file ("half_train.json#/bodies/2/mass"), the offending value, the rule, and the fix, and is
// thrown as std::invalid_argument (the SDK turns it into RUMBLE_ERROR with this text).
#ifndef RUMBLE_VEHICLES_JSON_READER_HPP
#define RUMBLE_VEHICLES_JSON_READER_HPP

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace rumble::vehicles {

/// Standard gravity [m/s^2]; the same value as single_wheel so that vehicles compare exactly.
inline constexpr double kStandardGravity = 9.81;

/// "<where>: <what>, got <value>; <fix>" (parts left empty are dropped).
[[noreturn]] inline void fail(const std::string& where, const std::string& what,
                              const std::string& got = {}, const std::string& fix = {}) {
  std::string m = where + ": " + what;
  if (!got.empty()) m += ", got " + got;
  if (!fix.empty()) m += "; " + fix;
  throw std::invalid_argument(m);
}

/// A JSON value as the user wrote it (numbers in shortest round-trip form).
inline std::string shown(const nlohmann::json& v) {
  return v.dump();
}

/// Levenshtein distance, for "did you mean".
inline std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

/// The closest candidate when it is close enough to be a typo, else nothing.
inline std::optional<std::string> closest(const std::string& word,
                                          const std::vector<std::string>& candidates) {
  std::optional<std::string> best;
  std::size_t best_distance = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const std::string& c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  return best;
}

/// " (did you mean "x"?)" or "".
inline std::string did_you_mean(const std::string& word,
                                const std::vector<std::string>& candidates) {
  const std::optional<std::string> c = closest(word, candidates);
  return c ? " (did you mean \"" + *c + "\"?)" : std::string();
}

/// Reads one JSON object; finish() refuses keys nobody asked for.
class ObjectReader {
 public:
  /// where: the object's pointer, e.g. "params/bodies/2".
  ObjectReader(const nlohmann::json& object, std::string where)
      : j_(object), where_(std::move(where)) {
    if (!j_.is_object()) fail(where_, "expected an object", shown(j_));
  }

  const std::string& where() const { return where_; }
  std::string at(const std::string& key) const { return where_ + "/" + key; }
  bool has(const char* key) const { return j_.contains(key) && !j_.at(key).is_null(); }

  /// The raw value (nullptr when absent); marks the key as known.
  const nlohmann::json* value(const char* key) {
    known_.insert(key);
    return has(key) ? &j_.at(key) : nullptr;
  }
  const nlohmann::json& required(const char* key, const char* meaning) {
    const nlohmann::json* v = value(key);
    if (v == nullptr) fail(where_, std::string("missing key \"") + key + "\"", {}, meaning);
    return *v;
  }

  double number(const char* key, const char* meaning) {
    return as_number(required(key, meaning), key);
  }
  double number_or(const char* key, double fallback) {
    const nlohmann::json* v = value(key);
    return v == nullptr ? fallback : as_number(*v, key);
  }
  /// A value > 0 (masses, stiffnesses, lengths); unit like "kg".
  double positive(const char* key, const char* unit, const char* meaning) {
    return check_positive(number(key, meaning), key, unit, meaning);
  }
  double positive_or(const char* key, double fallback, const char* unit, const char* meaning) {
    return check_positive(number_or(key, fallback), key, unit, meaning);
  }
  /// A value >= 0 (damping, inertia, gravity).
  double non_negative_or(const char* key, double fallback, const char* unit, const char* meaning) {
    const double x = number_or(key, fallback);
    if (!(x >= 0.0)) fail(at(key), std::string("must be >= 0 ") + unit, shown(j_.at(key)), meaning);
    return x;
  }
  std::string string(const char* key, const char* meaning) {
    const nlohmann::json& v = required(key, meaning);
    if (!v.is_string()) fail(at(key), "expected a string", shown(v), meaning);
    return v.get<std::string>();
  }
  std::string string_or(const char* key, const std::string& fallback) {
    const nlohmann::json* v = value(key);
    if (v == nullptr) return fallback;
    if (!v->is_string()) fail(at(key), "expected a string", shown(*v));
    return v->get<std::string>();
  }
  /// An array (possibly empty when absent and optional).
  const nlohmann::json& array(const char* key, bool required_key, const char* meaning) {
    static const nlohmann::json kEmpty = nlohmann::json::array();
    const nlohmann::json* v = required_key ? &required(key, meaning) : value(key);
    if (v == nullptr) return kEmpty;
    if (!v->is_array()) fail(at(key), "expected an array", shown(*v), meaning);
    return *v;
  }

  /// Refuses unknown keys, suggesting the closest known one.
  void finish() const {
    const std::vector<std::string> names(known_.begin(), known_.end());
    for (const auto& item : j_.items()) {
      if (known_.count(item.key()) != 0) continue;
      std::string allowed;
      for (const std::string& n : names) allowed += (allowed.empty() ? "" : ", ") + n;
      fail(at(item.key()), "unknown key" + did_you_mean(item.key(), names), {},
           "allowed keys here: " + allowed);
    }
  }

 private:
  double as_number(const nlohmann::json& v, const char* key) const {
    if (!v.is_number()) fail(at(key), "expected a number", shown(v));
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(at(key), "must be finite", shown(v));
    return x;
  }
  double check_positive(double x, const char* key, const char* unit, const char* meaning) const {
    if (!(x > 0.0)) fail(at(key), std::string("must be > 0 ") + unit, shown(j_.at(key)), meaning);
    return x;
  }

  const nlohmann::json& j_;
  std::string where_;
  std::set<std::string> known_;
};

}  // namespace rumble::vehicles

#endif  // RUMBLE_VEHICLES_JSON_READER_HPP
