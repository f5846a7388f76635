// The CLI's informational commands and its usage errors, as a user sees them.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <rumble/abi.h>

#include "cli_runner.hpp"

namespace rumble::testing {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

TEST(Cli, VersionAndHelp) {
  const CliResult v = run_rumble({"--version"});
  EXPECT_EQ(v.exit_code, 0);
  EXPECT_THAT(v.output, HasSubstr("rumble 0.1.0 (plugin ABI " + std::to_string(RUMBLE_ABI_MAJOR) +
                                  "." + std::to_string(RUMBLE_ABI_MINOR) + ")"));
  const CliResult h = run_rumble({"--help"});
  EXPECT_EQ(h.exit_code, 0);
  EXPECT_THAT(h.output, HasSubstr("usage: rumble"));
}

TEST(Cli, UnknownCommandListsCommands) {
  const CliResult r = run_rumble({"rnu"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("rumble: error: unknown command 'rnu'; commands: "));
  EXPECT_THAT(r.output, HasSubstr("run"));
}

TEST(Cli, UnknownOptionAndBadLogLevel) {
  EXPECT_THAT(
      run_rumble({"run", "x.json", "--fast"}).output,
      HasSubstr("unknown option '--fast'; options here: --allow-outside-results, --no-plots, "
                "--no-progress, --overwrite, --yes, --output, --set"));
  const CliResult r = run_rumble({"--log-level", "loud", "plugins"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("--log-level loud is not a level; choose trace, debug, info"));
  const CliResult missing = run_rumble({"plugins", "--log-level"});
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_THAT(missing.output, HasSubstr("--log-level needs a level; see rumble --help"));
}

// --log-level is global but may follow the command, where users tend to put it.
TEST(Cli, LogLevelAfterTheCommand) {
  const auto dir = scratch_directory("log_level_after_command");
  const auto scenario = write_scenario(dir, small_scenario()).string();
  const CliResult quiet = run_rumble({"run", scenario, "--no-progress", "--log-level", "warn"});
  EXPECT_EQ(quiet.exit_code, 0) << quiet.output;
  EXPECT_THAT(quiet.output, Not(HasSubstr("run completed")));
  const CliResult chatty = run_rumble({"run", scenario, "--log-level=info", "--no-progress"});
  EXPECT_EQ(chatty.exit_code, 0) << chatty.output;
  EXPECT_THAT(chatty.output, HasSubstr("run completed"));
}

TEST(Cli, PluginsListsInTreeTypes) {
  const CliResult r = run_rumble({"plugins"});
  EXPECT_EQ(r.exit_code, 0);
  for (const char* type : {"vehicle single_wheel", "soil winkler", "coupler gauss_seidel",
                           "coupler jacobi", "coupler implicit"})
    EXPECT_THAT(r.output, HasSubstr(type));
  const CliResult j = run_rumble({"plugins", "--format", "json"});
  EXPECT_EQ(j.exit_code, 0);
  EXPECT_TRUE(nlohmann::json::accept(j.output)) << j.output;
}

// Commands other than `rumble plugins` load a plugin only when the scenario uses one of its
// types (its manifest says which): validating a Winkler scenario never loads the FEM soil, whose
// gmsh and PETSc took 0.3 s of every command.
TEST(Cli, ValidateLoadsOnlyThePluginsTheScenarioUses) {
  const auto dir = scratch_directory("loads_what_it_uses");
  const auto scenario = write_scenario(dir, small_scenario()).string();
  const CliResult r = run_rumble({"--log-level", "debug", "validate", scenario});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("winkler.so at its first use"));
  EXPECT_THAT(r.output, HasSubstr("single_wheel.so at its first use"));
  EXPECT_THAT(r.output, Not(HasSubstr("fem.so")));
}

TEST(Cli, PluginsManifestNeedsAnOutput) {
  const CliResult r = run_rumble({"plugins", "--manifest", "x.so"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("--manifest x.so needs --output FILE: where to write the "
                                  "manifest"));
}

TEST(Cli, SchemaShowsUnitsAndSuggestsTypes) {
  const CliResult r = run_rumble({"schema", "single_wheel"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("static_load"));
  EXPECT_THAT(r.output, HasSubstr("[N]"));
  const CliResult bad = run_rumble({"schema", "singel_wheel"});
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_THAT(bad.output, HasSubstr("unknown type 'singel_wheel'"));
  EXPECT_THAT(bad.output, HasSubstr("did you mean \"single_wheel\"?"));
}

}  // namespace
}  // namespace rumble::testing
