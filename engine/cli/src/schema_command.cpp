// `rumble schema [TYPE] [--json]`: the parameters of a plugin type; without TYPE, the types.
#include <iostream>
#include <stdexcept>

#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "core/errors.hpp"
#include "plugin/registry.hpp"
#include "scenario/did_you_mean.hpp"
#include "scenario/scenario.hpp"

namespace rumble::cli {

int schema_command(const std::vector<std::string>& args) {
  const Arguments a(args, {"json"}, {});
  if (a.positional().size() > 1) throw UsageError("usage: rumble schema [TYPE] [--json]");
  PluginRegistry registry;
  registry.load_default_directories();
  if (a.positional().empty()) {  // the types there are, by kind
    if (a.flag("json")) {
      nlohmann::json out = nlohmann::json::object();
      for (const rumble_kind kind : {RUMBLE_KIND_VEHICLE, RUMBLE_KIND_SOIL, RUMBLE_KIND_COUPLER})
        out[kind_name(kind)] = registry.type_names(kind);
      std::cout << out.dump(2) << '\n';
      return kExitOk;
    }
    std::cout << "usage: rumble schema TYPE [--json]; the types:\n";
    for (const rumble_kind kind : {RUMBLE_KIND_VEHICLE, RUMBLE_KIND_SOIL, RUMBLE_KIND_COUPLER}) {
      const auto names = registry.type_names(kind);
      std::cout << "  " << kind_name(kind) << ": "
                << (names.empty() ? std::string("(none)") : scenario::join(names)) << '\n';
    }
    return kExitOk;
  }
  const std::string& name = a.positional()[0];
  for (const ComponentType& t : registry.types()) {
    if (t.type_name == name) {
      try {
        scenario::print_schema(std::cout, t, a.flag("json"));
      } catch (const std::runtime_error& e) {  // the plugin's schema is not JSON
        throw PluginLoadError(e.what());
      }
      return kExitOk;
    }
  }
  std::vector<std::string> known;
  for (const ComponentType& t : registry.types()) known.push_back(t.type_name);
  const auto guess = scenario::closest_match(name, known);
  std::cerr << "rumble: error: unknown type '" << name
            << "'\n    hint: " << (guess ? "did you mean \"" + *guess + "\"? " : std::string())
            << "known types: " << scenario::join(known) << '\n';
  return kExitConfig;
}

}  // namespace rumble::cli
