// `rumble validate FILE [--format text|json] [--no-load] [--yes]`: every error of a scenario,
// nothing run.
#include <iostream>

#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "cli/scenario_prepare.hpp"
#include "core/errors.hpp"

namespace rumble::cli {
namespace {

/// A failure before the diagnostics (a library of /plugins that does not load, a --set that
/// does not apply) in the report's JSON form, so that a tool reading --format json always gets
/// JSON on stdout.
void print_load_error(const std::string& file, const std::string& message) {
  scenario::Diagnostic d;
  d.message = message;
  scenario::print_diagnostics(std::cout, nullptr, file, {d}, scenario::Format::kJson);
}

}  // namespace

int validate_command(const std::vector<std::string>& args) {
  const Arguments a(args, {"no-load", "yes"}, {"format"}, {"set"});
  if (a.positional().size() != 1) {
    throw UsageError(
        "usage: rumble validate FILE [--format text|json] [--no-load] [--yes] "
        "[--set POINTER=VALUE ...]");
  }
  const bool json = a.choice("format", {"text", "json"}, "text") == "json";
  const std::string& file = a.positional()[0];
  scenario::CheckOptions options;
  options.load_plugins = !a.flag("no-load");
  options.size_confirmed = a.flag("yes");
  PluginRegistry registry;
  std::optional<scenario::Document> doc;
  try {
    std::vector<scenario::Override> overrides;
    for (const std::string& set : a.values("set"))
      overrides.push_back(scenario::parse_set_option(set));
    doc = prepare_scenario(file, registry, json ? scenario::Format::kJson : scenario::Format::kText,
                           overrides, options);
  } catch (const PluginLoadError& e) {
    if (!json) throw;
    print_load_error(file, e.what());
    return kExitPluginLoad;
  } catch (const ConfigError& e) {
    if (!json) throw;
    print_load_error(file, e.what());
    return kExitConfig;
  }
  if (!doc) return kExitConfig;
  if (!json) {
    std::cout << file << ": valid"
              << (options.load_plugins
                      ? ""
                      : " (--no-load: component types, params and plugins not checked)")
              << '\n';
  }
  return kExitOk;
}

}  // namespace rumble::cli
