#include "cli/commands.hpp"

#include <rumble/abi.h>

#include <cstdio>
#include <iostream>
#include <map>
#include <optional>

#include "cli/arguments.hpp"
#include "cli/exit_codes.hpp"
#include "cli/rank_server.hpp"
#include "core/errors.hpp"
#include "core/logging.hpp"
#include "core/thread_waits.hpp"
#include "parallel/mpi_session.hpp"

namespace rumble::cli {
namespace {

constexpr const char* kUsage = R"(rumble: railway ground-vibration co-simulation

usage: rumble [--log-level LEVEL] COMMAND [ARGS]   (--log-level may also follow the command)

commands:
  run FILE [--output DIR] [--overwrite] [--allow-outside-results] [--yes] [--no-progress]
           [--no-plots] [--set POINTER=VALUE ...]
                                    validate, then run a scenario; results go to outputs.directory
                                    inside the scenario's folder (elsewhere: --output DIR, or
                                    --allow-outside-results); a rerun replaces its own results
                                    there; --overwrite: also another scenario's, keeping files
                                    rumble did not write; --set: replace the value at a JSON
                                    pointer first (repeatable), e.g. --set /soil/params/E=1e7
  validate FILE [--format text|json] [--no-load] [--set POINTER=VALUE ...]
                                    check a scenario without running it (all errors at once);
                                    --no-load: without loading its plugins or building its parts
  study FILE [--jobs N] [--force] [--dry-run] [--no-report] [--yes] [--allow-outside-results]
                                    run a study: the product of scenario variations and/or a list,
                                    N runs at once as processes, skipping runs that are up to
                                    date (--force: rerun all; --dry-run: list them); docs/study.md
  plugins [--format text|json]      list plugin libraries and the types they provide
  schema [TYPE] [--json]            the parameters of a type: units, defaults, ranges; without
                                    TYPE, the known types
  mesh FILE [--output DIR] [--ranks N] [--allow-outside-results]
                                    build the scenario's soil on its footprints without running:
                                    its report in the log, its mesh in DIR/mesh.vtu (FEM soil)
  soil-frf FILE [options]           receptance of the scenario's soil at its footprints (CSV)
  calibrate FILE [options]          fit a reduced soil's parameters to a target soil's receptance
  stability FILE [--macro-steps LIST] [--output FILE.json]
                                    spectral radius of one gauss_seidel and jacobi macro step,
                                    linearized at rest, for the scenario's track and linear soil
  post RESULTS_DIR [options]        recompute a run's vibration indicators (PPV, spectra, KB,
                                    third-octave levels, guide values, wavelets) into
                                    RESULTS_DIR/post; `run` does it after every run with receivers
  new-plugin KIND NAME [DIR]        start a plugin project (KIND soil, vehicle or coupler) in DIR
                                    (default ./NAME) from the SDK's template, with its own test

  help [COMMAND]                    this text, or one command's options and their defaults
                                    (also: rumble COMMAND --help)

options:
  --log-level LEVEL   trace, debug, info (default), warn, error, off
  --version           print the version
  --help, -h          this text

plugins are found in the engine's plugin directory, in RUMBLE_PLUGIN_PATH (':'-separated
directories or files) and in a scenario's "plugins" list.
exit codes: 0 ok, 1 configuration or usage error, 2 plugin load error, 3 run failed.
)";

using Command = int (*)(const std::vector<std::string>&);

std::map<std::string, Command>& command_table() {
  static std::map<std::string, Command> table{{"run", &run_command},
                                              {"validate", &validate_command},
                                              {"plugins", &plugins_command},
                                              {"schema", &schema_command},
                                              {"mesh", &mesh_command},
                                              {"soil-frf", &soil_frf_command},
                                              {"stability", &stability_command},
                                              {"calibrate", &calibrate_command},
                                              {"new-plugin", &new_plugin_command},
                                              {"post", &post_command},
                                              {"study", &study_command}};
  return table;
}

/// Takes --log-level out of args and sets it: it is global and may stand anywhere ("rumble run
/// x.json --log-level warn" too).
void take_log_level(std::vector<std::string>& args) {
  for (std::size_t j = 0; j < args.size();) {
    std::string level;
    if (args[j].rfind("--log-level=", 0) == 0) {
      level = args[j].substr(12);
      args.erase(args.begin() + static_cast<long>(j));
    } else if (args[j] == "--log-level") {
      if (j + 1 == args.size()) throw UsageError("--log-level needs a level; see rumble --help");
      level = args[j + 1];
      args.erase(args.begin() + static_cast<long>(j), args.begin() + static_cast<long>(j) + 2);
    } else {
      ++j;
      continue;
    }
    if (!set_log_level(level)) {
      throw UsageError("--log-level " + level +
                       " is not a level; choose trace, debug, info, warn, error or off");
    }
  }
}

/// The other global options, which come before the command: --help and --version print and
/// give the exit code; otherwise nullopt, and `command` is where the command stands.
std::optional<int> global_options(const std::vector<std::string>& args, std::size_t& command) {
  std::size_t& i = command;
  for (; i < args.size() && (args[i].rfind("--", 0) == 0 || args[i] == "-h"); ++i) {
    const std::string& a = args[i];
    if (a == "--help" || a == "-h") {
      std::cout << kUsage;
      return kExitOk;
    }
    if (a == "--version") {
      std::cout << "rumble " << RUMBLE_VERSION << " (plugin ABI " << RUMBLE_ABI_MAJOR << "."
                << RUMBLE_ABI_MINOR << ")\n";
      return kExitOk;
    }
    throw UsageError("unknown option '" + a + "'; see rumble --help");
  }
  return std::nullopt;
}

/// The command named `name` (nullptr for help); throws UsageError listing them for another name.
Command find_command(const std::string& name) {
  const auto it = command_table().find(name);
  if (it == command_table().end() && name != "help") {
    std::string known;
    for (const auto& [k, v] : command_table()) known += (known.empty() ? "" : ", ") + k;
    throw UsageError("unknown command '" + name + "'; commands: " + known + ", help");
  }
  return it == command_table().end() ? nullptr : it->second;
}

/// `rumble COMMAND --help`: prints that command's options, whatever else was given; false when
/// --help is not among its arguments.
bool printed_command_help(const std::string& name, const std::vector<std::string>& rest) {
  for (const std::string& a : rest) {
    if (a == "--help" || a == "-h") {
      const char* text = command_help(name);
      std::cout << (text != nullptr ? text : kUsage);
      return true;
    }
  }
  return false;
}

/// `rumble help [COMMAND]`.
int help_command(const std::vector<std::string>& rest) {
  if (rest.empty()) {
    std::cout << kUsage;
    return kExitOk;
  }
  const char* text = command_help(rest.front());
  if (text == nullptr)
    throw UsageError("help: unknown command '" + rest.front() + "'; see rumble --help");
  std::cout << text;
  return kExitOk;
}

/// The command line's command, run in this process; its exit code (every error caught).
int command_in_process(std::vector<std::string>& args) {
  try {
    take_log_level(args);
    std::size_t i = 0;
    if (const std::optional<int> exit = global_options(args, i)) return *exit;
    if (i == args.size()) {
      std::cerr << kUsage;
      return kExitConfig;
    }
    const std::string name = args[i];
    const std::vector<std::string> rest(args.begin() + static_cast<long>(i) + 1, args.end());
    const Command command = find_command(name);
    if (printed_command_help(name, rest)) return kExitOk;
    if (name == "help") return help_command(rest);
    return command(rest);
  } catch (const UsageError& e) {
    std::cerr << "rumble: error: " << e.what() << '\n';
    return kExitConfig;
  } catch (const ConfigError& e) {
    std::cerr << "rumble: error: " << e.what() << '\n';
    return kExitConfig;
  } catch (const PluginLoadError& e) {
    std::cerr << "rumble: error: " << e.what() << '\n';
    return kExitPluginLoad;
  } catch (const std::exception& e) {
    std::cerr << "rumble: error: " << e.what() << '\n';
    return kExitRunFailed;
  }
}

/// Under an MPI launcher (decision 0012): rank 0 is the engine, with MPI started before anything
/// so that the other ranks can meet it; the other ranks serve until rank 0 releases them.
int launched_command(std::vector<std::string>& args) {
  if (!parallel::launched()) return command_in_process(args);
  try {
    parallel::start();
    if (parallel::world_rank() > 0) {
      serve_rank_zero();
      return kExitOk;
    }
  } catch (const std::exception& e) {
    std::cerr << "rumble: error: " << e.what() << '\n';
    return kExitRunFailed;
  }
  return command_in_process(args);
}

}  // namespace

int main(int argc, char** argv) {
  prefer_passive_thread_waits();  // before any plugin loads OpenMP (core/thread_waits.hpp)
  std::vector<std::string> args(argv + 1, argv + argc);
  const int code = launched_command(args);
  parallel::finish();  // after every plugin instance is gone (decision 0012)
  return code;
}

}  // namespace rumble::cli