// One finding about a scenario: where (JSON pointer, line:col), what, and how to fix it.
#pragma once

#include <cstddef>
#include <string>
#include <utility>

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

/// A finding without a position (the caller places it in the text).
inline Diagnostic finding(std::string pointer, std::string message, std::string hint = "",
                          Diagnostic::Severity severity = Diagnostic::Severity::kError) {
  Diagnostic d;
  d.severity = severity;
  d.pointer = std::move(pointer);
  d.message = std::move(message);
  d.hint = std::move(hint);
  return d;
}

}  // namespace rumble::scenario
