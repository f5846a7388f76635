// What the --set fuzz target checks for one input (the text of one `--set POINTER=VALUE` option),
// shared by the libFuzzer target (fuzz_target.cpp, preset "fuzz") and the replay test of the
// other presets (replay_test.cpp).
#pragma once

#include <string>
#include <string_view>

namespace rumble::fuzz {

/// Puts `option` (up to its first NUL byte: a command-line argument ends there) through what
/// `rumble validate --no-load --set OPTION` does with a valid scenario
/// (tests/scenario/valid/minimal.json), from memory: parse_set_option, apply_override, then the
/// whole check of the result. Returns "" when every property holds, else what broke:
///   - a refusal is a ConfigError whose message starts with the option as given ("--set ...",
///     cut at 80 characters) when the text is UTF-8, and says which byte is not when it is not;
///     nothing else escapes, at any step;
///   - an accepted option has the pointer before the first '=' and the value JSON parses from
///     the rest (a bare word: the text itself); written back as the study writes it for a run's
///     child process (POINTER=compact JSON), it parses to the same pointer and value;
///   - applied, the scenario is the original with exactly that pointer changed: the value is
///     there, and taking it out again (or the members it created) gives the original back;
///   - checking the result gives diagnostics with messages and lines inside the text, those
///     at or below the set value end with "(set by --set)", and both reports print.
std::string check_set_option(std::string_view input);

}  // namespace rumble::fuzz
