// `rumble validate FILE [--format text|json]`: every error of a scenario, nothing run.
#include <iostream>

#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "cli/scenario_prepare.hpp"

namespace rumble::cli {

int validate_command(const std::vector<std::string>& args) {
  const Arguments a(args, {}, {"format"}, {"set"});
  if (a.positional().size() != 1)
    throw UsageError("usage: rumble validate FILE [--format text|json] [--set POINTER=VALUE ...]");
  const bool json = a.choice("format", {"text", "json"}, "text") == "json";
  std::vector<scenario::Override> overrides;
  for (const std::string& set : a.values("set"))
    overrides.push_back(scenario::parse_set_option(set));
  PluginRegistry registry;
  const auto doc =
      prepare_scenario(a.positional()[0], registry,
                       json ? scenario::Format::kJson : scenario::Format::kText, overrides);
  if (!doc) return kExitConfig;
  if (!json) std::cout << a.positional()[0] << ": valid\n";
  return kExitOk;
}

}  // namespace rumble::cli
