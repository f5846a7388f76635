// `rumble schema TYPE [--json]`: the parameters of a plugin type.
#include <iostream>

#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "plugin/registry.hpp"
#include "scenario/did_you_mean.hpp"
#include "scenario/scenario.hpp"

namespace rumble::cli {

int schema_command(const std::vector<std::string>& args) {
  const Arguments a(args, {"json"}, {});
  if (a.positional().size() != 1) throw UsageError("usage: rumble schema TYPE [--json]");
  const std::string& name = a.positional()[0];
  PluginRegistry registry;
  registry.load_default_directories();
  for (const ComponentType& t : registry.types()) {
    if (t.type_name == name) {
      scenario::print_schema(std::cout, t, a.flag("json"));
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
