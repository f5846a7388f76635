#include "scenario/check_file.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <optional>
#include <rumble/host_resources.hpp>

#include "plugin/registry.hpp"
#include "scenario/capability_check.hpp"
#include "scenario/component_check.hpp"
#include "scenario/relation_checks.hpp"
#include "scenario/run_size.hpp"
#include "scenario/run_spec.hpp"
#include "scenario/validate.hpp"

namespace rumble::scenario {
namespace {

namespace fs = std::filesystem;

/// The results directory a run would write (outputs.directory beside the scenario) can be used:
/// a file in its place, or a directory nobody may write in, was found only when the run began.
/// Nothing is created here; a missing directory is judged by its nearest existing ancestor.
std::optional<Diagnostic> results_directory_unusable(const Document& doc) {
  const fs::path dir = results_directory(doc.json, doc.path);
  const std::string given = doc.json.at("outputs").at("directory").get<std::string>();
  const std::string hint =
      "name a directory you may write in (created when missing), or give rumble run --output DIR";
  fs::path existing = dir.empty() ? fs::path(".") : dir;
  std::error_code ec;
  while (!fs::exists(fs::symlink_status(existing, ec)) && existing.has_parent_path() &&
         existing.parent_path() != existing)
    existing = existing.parent_path();
  if (!fs::exists(existing, ec)) existing = ".";  // a relative path: the current directory
  const auto quoted = [](const fs::path& p) { return "\"" + p.lexically_normal().string() + "\""; };
  if (!fs::is_directory(existing, ec)) {
    return finding("/outputs/directory",
                   existing == dir ? quoted(dir) + " is a file, not a directory"
                                   : "cannot create " + quoted(dir) + ": " + quoted(existing) +
                                         " is a file, not a directory",
                   hint);
  }
  if (::access(existing.c_str(), W_OK | X_OK) != 0) {
    return finding("/outputs/directory",
                   (existing == dir ? "cannot write in " + quoted(dir)
                                    : "cannot create " + quoted(dir) + " in " + quoted(existing)) +
                       ": " + std::strerror(errno) + " (outputs.directory is " +
                       nlohmann::json(given).dump() + ")",
                   hint);
  }
  return std::nullopt;
}

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
                                    std::vector<Override>& overrides, PluginRegistry& registry,
                                    const CheckOptions& options) {
  std::vector<Diagnostic> diagnostics;
  std::optional<Document> doc = load_document(path, diagnostics);
  if (!doc) {
    CheckedScenario c;
    c.diagnostics = std::move(diagnostics);
    return c;
  }
  return check_scenario_document(std::move(*doc), overrides, registry, options);
}

CheckedScenario check_scenario_document(Document document, std::vector<Override>& overrides,
                                        PluginRegistry& registry, const CheckOptions& options) {
  CheckedScenario c;
  c.doc = std::move(document);
  Document& doc = *c.doc;
  for (Override& o : overrides) apply_override(doc.json, o);
  if (options.load_plugins) load_scenario_plugins(doc, registry);
  c.diagnostics = validate(doc, registry, options.load_plugins);
  if (no_errors(c.diagnostics)) {
    for (Diagnostic& d : check_scenario_relations(doc.json))
      c.diagnostics.push_back(make_diagnostic(doc, d.pointer, d.message, d.hint, d.severity));
  }
  if (no_errors(c.diagnostics) && options.load_plugins) {  // (before a soil is built: meshed)
    for (Diagnostic& d : check_split_soil(doc.json, registry, options.ranks, options.whole_soil))
      c.diagnostics.push_back(make_diagnostic(doc, d.pointer, d.message, d.hint, d.severity));
  }
  // The run's size, from the scenario alone: before any component is built (a FEM soil meshes
  // in its constructor) and whether or not plugins are loaded.
  if (no_errors(c.diagnostics) && !options.size_confirmed) {
    std::vector<Diagnostic> size;
    for (Diagnostic& d : check_run_size(doc.json))
      size.push_back(make_diagnostic(doc, d.pointer, d.message, d.hint, d.severity));
    sort_diagnostics(size);
    c.diagnostics.insert(c.diagnostics.end(), size.begin(), size.end());
  }
  // A directory outside the scenario's folder is the command line's to allow (rumble run
  // refuses it, or the user consents and the run reports what it cannot create).
  if (no_errors(c.diagnostics) && options.results_directory) {
    if (auto outside = results_outside_scenario_folder(doc.json, doc.path)) {
      if (options.results_inside_folder)
        c.diagnostics.push_back(
            make_diagnostic(doc, outside->pointer, outside->message, outside->hint));
    } else if (auto d = results_directory_unusable(doc)) {
      c.diagnostics.push_back(make_diagnostic(doc, d->pointer, d->message, d->hint));
    }
  }
  // What the machine has free, whatever --yes says (past it the run cannot end well).
  if (no_errors(c.diagnostics) && options.machine_room) {
    const fs::path dir = options.output_directory ? *options.output_directory
                                                  : results_directory(doc.json, doc.path);
    const MachineRoom room{available_memory_bytes(), free_disk_bytes(dir.string()),
                           dir.lexically_normal().string()};
    for (Diagnostic& d : check_machine_room(doc.json, room))
      c.diagnostics.push_back(make_diagnostic(doc, d.pointer, d.message, d.hint, d.severity));
  }
  if (no_errors(c.diagnostics) && options.load_plugins) {  // built from a scenario that is right
    for (Diagnostic& d :
         check_components(doc.json, doc.path.parent_path(), registry, options.keep_soils))
      c.diagnostics.push_back(make_diagnostic(doc, d.pointer, d.message, d.hint, d.severity));
  }
  if (!overrides.empty()) {
    for (Diagnostic& d : c.diagnostics) d.message += override_note(overrides, d.pointer);
  }
  return c;
}

}  // namespace rumble::scenario
