// Validation of a whole scenario: the engine's schema, the component types in the plugin
// registry, each component's params against its plugin's schema, and the engine's own
// cross-field rules; ALL problems are collected. Also fills every declared default.
#pragma once

#include <string>
#include <vector>

#include "scenario/diagnostic.hpp"
#include "scenario/document.hpp"

namespace rumble {
class PluginRegistry;
}

namespace rumble::scenario {

/// More than this many errors are cut, with a last diagnostic saying how many were left out.
inline constexpr std::size_t kMaxDiagnostics = 100;
/// A document with more JSON values than this is refused: scenario files hold parameters, and
/// the error list of a huge invalid array would not fit in memory.
inline constexpr std::size_t kMaxValues = 200000;

/// Loads the libraries listed in /plugins (paths relative to the scenario file) into the
/// registry. Entries that are not non-empty strings are skipped (validate() reports them).
/// Throws PluginLoadError whose message starts with "<file>: /plugins/<i>: ".
void load_scenario_plugins(const Document& doc, PluginRegistry& registry);

/// Checks everything and returns the diagnostics sorted by position (empty = valid). Fills
/// every default declared by the engine's and the plugins' schemas into doc.json, nested
/// objects included, and /vehicles/<i>/name = "vehicle<i>" where absent. check_plugins false
/// (`rumble validate --no-load`): the engine's schema only; component types, their params and
/// capabilities are not checked (no plugin is loaded to check them against).
std::vector<Diagnostic> validate(Document& doc, const PluginRegistry& registry,
                                 bool check_plugins = true);

/// A diagnostic at `pointer` with the line:col of its value in doc.text (of the nearest
/// ancestor that is in the text when the value itself is not, e.g. a filled-in default).
Diagnostic make_diagnostic(const Document& doc, std::string pointer, std::string message,
                           std::string hint = "",
                           Diagnostic::Severity severity = Diagnostic::Severity::kError);

/// Sorts by line, column (position-less diagnostics first), keeping the order of equals.
void sort_diagnostics(std::vector<Diagnostic>& diagnostics);

}  // namespace rumble::scenario
