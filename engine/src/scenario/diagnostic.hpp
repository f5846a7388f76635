// One finding about a scenario: where (JSON pointer, line:col), what, and how to fix it.
#pragma once

#include <cstddef>
#include <string>

namespace rumble::scenario {

struct Diagnostic {
  enum class Severity { kError, kWarning };
  Severity severity = Severity::kError;
  std::string pointer;     // JSON pointer into the scenario, e.g. "/soil/params/E"; "" = whole file
  std::size_t line = 0;    // 1-based; 0 when unknown
  std::size_t column = 0;  // 1-based; 0 when unknown
  std::string message;     // "must be > 0, got -2.5e7"
  std::string hint;        // "did you mean \"winkler\"? known soil types: clm, winkler"; may be ""
};

}  // namespace rumble::scenario
