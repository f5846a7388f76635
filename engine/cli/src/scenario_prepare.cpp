#include "cli/scenario_prepare.hpp"

#include <iostream>

#include "core/cpu_affinity.hpp"
#include "scenario/check_file.hpp"
#include "track_spec/footprint_layout.hpp"

namespace rumble::cli {

std::optional<scenario::Document> prepare_scenario(const std::filesystem::path& path,
                                                   PluginRegistry& registry,
                                                   scenario::Format format,
                                                   std::vector<scenario::Override> overrides,
                                                   const scenario::CheckOptions& options) {
  if (options.load_plugins) registry.load_default_directories();
  scenario::CheckedScenario checked =
      scenario::check_scenario_file(path, overrides, registry, options);
  std::optional<scenario::Document>& doc = checked.doc;
  const std::vector<scenario::Diagnostic>& diagnostics = checked.diagnostics;
  const bool ok = checked.ok();
  if (!diagnostics.empty() || format == scenario::Format::kJson) {
    scenario::print_diagnostics(format == scenario::Format::kJson ? std::cout : std::cerr,
                                doc ? &*doc : nullptr, path, diagnostics, format);
  }
  if (!ok) return std::nullopt;
  return std::move(doc);
}

ScenarioSoil soil_on_footprints(const scenario::Document& doc, const PluginRegistry& registry,
                                BuiltSoils* built) {
  ScenarioSoil s;
  s.layout = footprint_layout(TrackConfig::from_json(doc.json.at("track")));
  const auto& soil = doc.json.at("soil");
  const std::string type = soil.at("type").get<std::string>();
  const nlohmann::json params = soil.value("params", nlohmann::json::object());
  s.type = registry.find(RUMBLE_KIND_SOIL, type);
  const std::filesystem::path dir = doc.path.parent_path();
  s.soil = built != nullptr ? built->take_or_lay(*s.type, "/soil", params, dir, s.layout)
                            : lay_soil(*s.type, "/soil", params, dir, s.layout);
  // The soil runs alone in these commands (its receptance, its impulse responses, its stable
  // step): the machine's cores are its.
  s.soil->grant_threads(static_cast<unsigned>(usable_cpus()));
  return s;
}

}  // namespace rumble::cli
