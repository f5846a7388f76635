#include "scenario/check_file.hpp"

#include <algorithm>

#include "plugin/registry.hpp"
#include "scenario/component_check.hpp"
#include "scenario/relation_checks.hpp"
#include "scenario/validate.hpp"

namespace rumble::scenario {
namespace {

bool no_errors(const std::vector<Diagnostic>& diagnostics) {
  return std::none_of(diagnostics.begin(), diagnostics.end(), [](const Diagnostic& d) {
    return d.severity == Diagnostic::Severity::kError;
  });
}

}  // namespace

bool CheckedScenario::ok() const {
  return doc.has_value() && no_errors(diagnostics);
}

CheckedScenario check_scenario_file(const std::filesystem::path& path,
                                    std::vector<Override>& overrides, PluginRegistry& registry) {
  CheckedScenario c;
  c.doc = load_document(path, c.diagnostics);
  if (!c.doc) return c;
  Document& doc = *c.doc;
  for (Override& o : overrides) apply_override(doc.json, o);
  load_scenario_plugins(doc, registry);
  c.diagnostics = validate(doc, registry);
  if (no_errors(c.diagnostics)) {
    for (Diagnostic& d : check_scenario_relations(doc.json))
      c.diagnostics.push_back(make_diagnostic(doc, d.pointer, d.message, d.hint, d.severity));
  }
  if (no_errors(c.diagnostics)) {  // the components are built from a scenario that is right
    for (Diagnostic& d : check_components(doc.json, doc.path.parent_path(), registry))
      c.diagnostics.push_back(make_diagnostic(doc, d.pointer, d.message, d.hint, d.severity));
  }
  if (!overrides.empty()) {
    for (Diagnostic& d : c.diagnostics) d.message += override_note(overrides, d.pointer);
  }
  return c;
}

}  // namespace rumble::scenario
