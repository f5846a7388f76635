// Values set from outside a scenario file before it is validated: `--set POINTER=VALUE` on
// `rumble run` and `rumble validate`, and the patches of a study's runs (study/). Each replaces the
// value at a JSON pointer (RFC 6901), creating missing object members; an array element must
// exist already. Diagnostics about a set value say where it came from. docs/scenario.md.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace rumble::scenario {

struct Override {
  std::string pointer;   // "/soil/params/E"
  nlohmann::json value;  // what replaces the value there
  /// How messages name this override ("--set /soil/params/E=1e7", "study.json /axes/0/...").
  std::string label;
  /// What set it, for the note on diagnostics: "(set by --set)".
  std::string origin = "--set";
  /// Filled by apply_override: the highest member it created, or `pointer` when none was created;
  /// diagnostics at or below it are about this override.
  std::string applied_at;
};

/// Parses the text of one --set option, "POINTER=VALUE": the value is JSON, or, when it is not
/// JSON and does not look like it (no leading '{', '[' or '"'), the text as a string. Throws
/// ConfigError naming the option, what is wrong and the fix.
Override parse_set_option(std::string_view text);

/// Checks that `pointer` is a JSON pointer that can name a value in a scenario (not "", starts
/// with '/', '~' only as ~0 or ~1); returns "" when it is, else what is wrong with it.
std::string pointer_problem(std::string_view pointer);

/// Replaces the value at o.pointer in `document` and sets o.applied_at. Throws ConfigError
/// naming o.label, the part of the pointer that fails and the fix.
void apply_override(nlohmann::json& document, Override& o);

/// " (set by ORIGIN)" when `pointer` lies at or below what one of the overrides set (the last
/// one that did), "" otherwise.
std::string override_note(const std::vector<Override>& overrides, std::string_view pointer);

/// "POINTER=VALUE", the value as compact JSON: the override's identity (results manifest).
std::string override_text(const Override& o);

}  // namespace rumble::scenario
