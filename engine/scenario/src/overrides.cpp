#include "scenario/overrides.hpp"

#include <cstddef>
#include <cstdio>

#include "core/errors.hpp"
#include "scenario/json_position.hpp"
#include "scenario/value_text.hpp"

namespace rumble::scenario {
namespace {

using nlohmann::json;

/// "a number", "an object" ... of a value, for "X is a number, not an object".
std::string kind_of(const json& v) {
  return v.is_boolean() ? "a boolean" : type_phrase(type_of(v));
}

/// The pointer of the first n tokens.
std::string prefix(const std::vector<std::string>& tokens, std::size_t n) {
  std::string p;
  for (std::size_t i = 0; i < n; ++i) p += "/" + escape_pointer_token(tokens[i]);
  return p;
}

/// An array index as RFC 6901 writes it: digits, no leading zero; nullopt otherwise.
std::optional<std::size_t> array_index(const std::string& token) {
  if (token.empty() || token.size() > 9 || (token.size() > 1 && token[0] == '0')) return {};
  std::size_t i = 0;
  for (const char c : token) {
    if (c < '0' || c > '9') return {};
    i = i * 10 + static_cast<std::size_t>(c - '0');
  }
  return i;
}

std::string indices(std::size_t size) {
  if (size == 0) return "it is empty";
  if (size == 1) return "it has 1 element, index 0";
  return "it has " + std::to_string(size) + " elements, indices 0 to " + std::to_string(size - 1);
}

}  // namespace

std::string pointer_problem(std::string_view pointer) {
  if (pointer.empty()) {
    return "the pointer is empty; name the value to replace, e.g. /soil/params/E (the whole "
           "scenario cannot be replaced)";
  }
  if (pointer[0] != '/') {
    return "\"" + truncate_text(pointer, 60) +
           "\" is not a JSON pointer: it starts with '/', e.g. /soil/params/E";
  }
  if (!split_pointer(pointer)) {
    return "\"" + truncate_text(pointer, 60) +
           "\" is not a JSON pointer: '~' must be followed by 0 (for '~') or 1 (for '/')";
  }
  return "";
}

Override parse_set_option(std::string_view text) {
  if (const auto bad = first_invalid_utf8(text)) {
    char hex[8];
    std::snprintf(hex, sizeof hex, "0x%02X", static_cast<unsigned char>(text[*bad]));
    throw ConfigError("--set " + short_json(json(std::string(text)), 80) + ": byte " + hex +
                      " at offset " + std::to_string(*bad) +
                      " is not UTF-8, and a scenario is UTF-8 text (RFC 8259); write the value "
                      "in UTF-8, or as a JSON string with \\u escapes, e.g. --set "
                      "'/name=\"caf\\u00e9\"'");
  }
  const std::string shown = "--set " + truncate_text(text, 80);
  const auto eq = text.find('=');
  if (eq == std::string_view::npos) {
    throw ConfigError(shown +
                      ": expected POINTER=VALUE, e.g. --set /soil/params/E=1.55e8 or "
                      "--set /coupling/type=jacobi");
  }
  Override o;
  o.pointer = std::string(text.substr(0, eq));
  o.label = shown;
  const std::string value(text.substr(eq + 1));
  if (const std::string problem = pointer_problem(o.pointer); !problem.empty()) {
    throw ConfigError(shown + ": " + problem);
  }
  if (value.empty()) {
    throw ConfigError(shown + ": no value after '='; write a JSON value, e.g. " + o.pointer +
                      "=1.5, or '" + o.pointer + "=\"\"' for an empty string");
  }
  try {
    o.value = json::parse(value);
  } catch (const json::exception& e) {
    const char first = value.find_first_not_of(" \t") == std::string::npos
                           ? ' '
                           : value[value.find_first_not_of(" \t")];
    if (first == '{' || first == '[' || first == '"') {
      std::string why = e.what();
      if (const auto at = why.find("parse error"); at != std::string::npos) why = why.substr(at);
      throw ConfigError(shown + ": the value is not valid JSON (" + why +
                        "); quote the whole option for the shell, e.g. --set '" + o.pointer +
                        "={\"k\": 1e8}'");
    }
    o.value = value;  // a bare word: a string
  }
  return o;
}

void apply_override(json& document, Override& o) {
  if (const std::string problem = pointer_problem(o.pointer); !problem.empty()) {
    throw ConfigError(o.label + ": " + problem);
  }
  const std::vector<std::string> tokens = *split_pointer(o.pointer);
  json* at = &document;
  o.applied_at.clear();
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const std::string& token = tokens[i];
    const bool last = i + 1 == tokens.size();
    const std::string here = prefix(tokens, i);
    if (at->is_object()) {
      if (!at->contains(token) && o.applied_at.empty()) o.applied_at = prefix(tokens, i + 1);
      json& next = (*at)[token];
      if (!last && next.is_null()) next = json::object();
      at = &next;
    } else if (at->is_array()) {
      const auto index = array_index(token);
      if (!index || *index >= at->size()) {
        throw ConfigError(
            o.label + ": " + (here.empty() ? std::string("the scenario") : here) +
            " is an array (" + indices(at->size()) + "), which has no element \"" +
            truncate_text(token, 30) + "\"; " +
            (index || token == "-"
                 ? "an override replaces an element but does not add one: add it in the "
                   "scenario file"
                 : "name an element by its index, e.g. " + here + "/0"));
      }
      at = &(*at)[*index];
    } else {
      throw ConfigError(o.label + ": " + here + " is " + kind_of(*at) +
                        ", not an object or array, so it has no member \"" +
                        truncate_text(token, 30) + "\"; set " + here +
                        " itself, or correct the pointer");
    }
  }
  *at = o.value;
  if (o.applied_at.empty()) o.applied_at = o.pointer;
}

std::string override_note(const std::vector<Override>& overrides, std::string_view pointer) {
  for (auto it = overrides.rbegin(); it != overrides.rend(); ++it) {
    const std::string& root = it->applied_at.empty() ? it->pointer : it->applied_at;
    if (pointer == root ||
        (pointer.size() > root.size() && pointer.substr(0, root.size()) == root &&
         pointer[root.size()] == '/')) {
      return " (set by " + it->origin + ")";
    }
  }
  return "";
}

std::string override_text(const Override& o) {
  return o.pointer + "=" + o.value.dump(-1, ' ', false, json::error_handler_t::replace);
}

}  // namespace rumble::scenario
