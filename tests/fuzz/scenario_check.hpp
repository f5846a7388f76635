// What the scenario fuzz target checks for one input, shared by the libFuzzer target
// (fuzz_target.cpp, preset "fuzz") and the replay test of the other presets (replay_test.cpp).
#pragma once

#include <string>
#include <string_view>

namespace rumble::fuzz {

/// Puts `text` through everything `rumble validate --no-load` does, from memory: parse (size,
/// nesting, syntax, duplicate keys), the engine's schema, the relations between fields, the run's
/// size, and both report formats. Returns "" when every property that must hold for any input
/// holds, else what broke:
///   - nothing escapes as an exception (validate --no-load has none to report);
///   - a text that does not load says why; every diagnostic has a message and a line inside the
///     text (or none: about the whole file), and a column only with a line;
///   - no data lost: every value nlohmann parsed is found at its pointer in the text by the
///     position index the diagnostics use, and a number or string found there parses back to
///     the same value;
///   - the JSON report parses back, with as many diagnostics as were found.
/// A crash, a sanitizer report or an input slower than the fuzzer's -timeout is found by the
/// fuzzer itself.
std::string check_scenario_text(std::string_view text);

}  // namespace rumble::fuzz
