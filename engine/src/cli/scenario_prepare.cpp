#include "cli/scenario_prepare.hpp"

#include <algorithm>
#include <iostream>

#include "scenario/component_check.hpp"
#include "scenario/relation_checks.hpp"
#include "track/footprint_layout.hpp"

namespace rumble::cli {

std::optional<scenario::Document> prepare_scenario(const std::filesystem::path& path,
                                                   PluginRegistry& registry,
                                                   scenario::Format format) {
  registry.load_default_directories();
  std::vector<scenario::Diagnostic> diagnostics;
  std::optional<scenario::Document> doc = scenario::load_document(path, diagnostics);
  if (doc) {
    scenario::load_scenario_plugins(*doc, registry);
    diagnostics = scenario::validate(*doc, registry);
    const bool schema_ok = std::none_of(diagnostics.begin(), diagnostics.end(), [](const auto& d) {
      return d.severity == scenario::Diagnostic::Severity::kError;
    });
    const auto no_errors = [&] {
      return std::none_of(diagnostics.begin(), diagnostics.end(), [](const auto& d) {
        return d.severity == scenario::Diagnostic::Severity::kError;
      });
    };
    if (schema_ok) {
      for (scenario::Diagnostic& d : check_scenario_relations(doc->json))
        diagnostics.push_back(
            scenario::make_diagnostic(*doc, d.pointer, d.message, d.hint, d.severity));
    }
    if (schema_ok && no_errors()) {  // the components are built from a scenario that is right
      for (scenario::Diagnostic& d :
           scenario::check_components(doc->json, doc->path.parent_path(), registry))
        diagnostics.push_back(
            scenario::make_diagnostic(*doc, d.pointer, d.message, d.hint, d.severity));
    }
  }
  const bool ok = doc && std::none_of(diagnostics.begin(), diagnostics.end(), [](const auto& d) {
                    return d.severity == scenario::Diagnostic::Severity::kError;
                  });
  if (!diagnostics.empty() || format == scenario::Format::kJson) {
    scenario::print_diagnostics(format == scenario::Format::kJson ? std::cout : std::cerr,
                                doc ? &*doc : nullptr, path, diagnostics, format);
  }
  if (!ok) return std::nullopt;
  return doc;
}

ScenarioSoil soil_on_footprints(const scenario::Document& doc, const PluginRegistry& registry) {
  ScenarioSoil s;
  s.layout = footprint_layout(TrackConfig::from_json(doc.json.at("track")));
  const auto& soil = doc.json.at("soil");
  s.type = registry.find(RUMBLE_KIND_SOIL, soil.at("type").get<std::string>());
  s.soil = std::make_unique<SoilInstance>(
      *s.type, "/soil", soil.value("params", nlohmann::json::object()), doc.path.parent_path());
  s.soil->accept_layout(s.layout);
  return s;
}

}  // namespace rumble::cli
