// Printing diagnostics: compiler-style text for people and editors, or JSON for tools and CI.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <vector>

#include "scenario/diagnostic.hpp"

namespace rumble::scenario {

struct Document;

enum class Format { kText, kJson };

/// Text, one diagnostic per line, then an indented hint line when there is one:
///   scenarios/x.json:27:18: error: /soil/params/E: must be > 0, got -2.5e7
///       hint: ...
/// and a summary line ("2 errors", "1 error, 1 warning"); nothing at all when the list is
/// empty. JSON: {"file", "diagnostics": [{"severity", "pointer", "line", "column", "message",
/// "hint"}], "errors", "warnings"}, line and column null when unknown.
/// `file` is printed as given. `doc` (may be null) supplies line:col for diagnostics that
/// have a pointer but no position yet.
void print_diagnostics(std::ostream& os, const Document* doc, const std::filesystem::path& file,
                       const std::vector<Diagnostic>& diagnostics, Format format);

}  // namespace rumble::scenario
