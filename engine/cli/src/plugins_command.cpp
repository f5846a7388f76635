// `rumble plugins`: the plugin libraries found and the types each provides.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "parallel/mpi_session.hpp"
#include "plugin/capabilities.hpp"
#include "plugin/manifest.hpp"
#include "plugin/registry.hpp"

namespace rumble::cli {
namespace {

namespace fs = std::filesystem;

/// The MPI the engine would start for a distributed soil (docs/decisions/0012), without starting
/// it; and, under a launcher, the rank count it was given.
std::string mpi_line() {
  std::string line = "MPI: " + parallel::library_version() + " (MPI " +
                     parallel::standard_version() + "), started only for a soil that uses it; ";
  if (!parallel::launched()) return line + "not launched by mpirun (one rank)";
  return line + "launched on " + std::to_string(parallel::launched_size()) + " ranks";
}

/// `--manifest LIB --output FILE`: the library loaded alone and its manifest written to FILE
/// (manifest.hpp; rumble_add_plugin() runs this after each link of a plugin). Written to a
/// temporary name and renamed, so that a reader never finds half a manifest.
int write_manifest(const std::string& library_file, const std::optional<std::string>& output) {
  if (!output) {
    throw UsageError("--manifest " + library_file +
                     " needs --output FILE: where to write the manifest (rumble_add_plugin() "
                     "writes <library>.manifest.json)");
  }
  PluginRegistry registry(PluginRegistry::Manifests::kIgnore);
  registry.load_library(library_file);
  const fs::path file = *output;
  const fs::path partial = file.string() + ".partial";
  {
    std::ofstream out(partial);
    out << manifest_text(*registry.libraries().front(), registry.types());
    if (!out.flush()) throw std::runtime_error("cannot write " + partial.string());
  }
  fs::rename(partial, file);
  return kExitOk;
}

}  // namespace

int plugins_command(const std::vector<std::string>& args) {
  const Arguments a(args, {}, {"format", "manifest", "output"});
  if (const auto library = a.value("manifest")) return write_manifest(*library, a.value("output"));
  const std::string format = a.choice("format", {"text", "json"}, "text");
  // Every library loaded, so that one which cannot be (a dependency missing) is listed as such
  // here, not only when a scenario first uses it.
  PluginRegistry registry(PluginRegistry::Manifests::kIgnore);
  registry.load_default_directories();
  if (format == "json") {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& lib : registry.libraries()) {
      nlohmann::json types = nlohmann::json::array();
      for (const ComponentType& t : registry.types())
        if (t.library == lib)
          types.push_back(
              {{"type", t.type_name},
               {"kind", kind_name(t.kind)},
               {"summary", t.summary},
               {"capabilities",
                {{"declared", t.capabilities.declared},
                 {"offers", capability_keys(t.capabilities.offers)},
                 {"soil_needs", capability_keys(t.capabilities.soil_needs)},
                 {"max_macro_step_s", t.capabilities.max_macro_step},
                 {"participants",
                  nlohmann::json::parse(t.capabilities.participants_json, nullptr, false)}}}});
      const PluginIdentity& id = lib->identity;
      out.push_back({{"plugin", id.name},
                     {"version", id.version},
                     {"abi", id.abi()},
                     {"build", id.build_fingerprint},
                     {"path", lib->path.string()},
                     {"origin", lib->origin},
                     {"types", types}});
    }
    // Skipped libraries are in the log (stderr), so stdout stays one JSON array of libraries.
    std::cout << out.dump(2) << '\n';
    return kExitOk;
  }
  std::cout << "plugin directory: " << PluginRegistry::builtin_plugin_directory().string() << '\n'
            << mpi_line() << '\n';
  if (registry.libraries().empty()) {
    std::cout << "no plugins found; build the project, or set RUMBLE_PLUGIN_PATH\n";
  }
  for (const auto& lib : registry.libraries()) {
    const PluginIdentity& id = lib->identity;
    std::cout << '\n'
              << id.name << ' ' << id.version << "  (ABI " << id.abi() << ")  "
              << lib->path.string() << "  (from " << lib->origin << ")\n"
              << "  built with: " << id.build_fingerprint << '\n';
    for (const ComponentType& t : registry.types()) {
      if (t.library != lib) continue;
      std::cout << "  " << kind_name(t.kind) << ' ' << t.type_name << ": " << t.summary << '\n';
      const Capabilities& c = t.capabilities;
      std::string offers;
      for (const std::string& key : capability_keys(c.offers))
        offers += (offers.empty() ? "" : ", ") + key;
      std::cout << "    offers: " << (offers.empty() ? "-" : offers)
                << (c.declared ? "" : " (ABI 1.0: derived, not declared)") << '\n';
      if (c.soil_needs != 0) {
        std::string needs;
        for (const std::string& key : capability_keys(c.soil_needs))
          needs += (needs.empty() ? "" : ", ") + key;
        std::cout << "    needs of every soil: " << needs << '\n';
      }
    }
  }
  if (!registry.skipped().empty()) {
    std::cout << "\nnot loaded (skipped; the plugins above are usable):\n";
    for (const SkippedPlugin& s : registry.skipped())
      std::cout << "  " << s.path.string() << "  (from " << s.origin << "): " << s.reason << '\n';
  }
  return kExitOk;
}

}  // namespace rumble::cli
