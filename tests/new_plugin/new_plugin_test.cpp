// `rumble new-plugin`: its refusals (exit code 1, with what, the value and the fix) and a scaffold
// of each kind from the build tree's share/rumble (files renamed, no template name left). And the
// one share/rumble lookup: the build tree has the plot scripts and templates where an install
// has them, and a rumble copied away from its share/ says where it looked, for templates and plot
// scripts alike, instead of falling back to the source tree.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace rumble::testing {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const fs::path kBuild = RUMBLE_TEST_BINARY_DIR;
const std::array<std::string, 6> kTemplateNames = {"template_soil",    "TemplateSoil",
                                                   "template_vehicle", "TemplateVehicle",
                                                   "template_coupler", "TemplateCoupler"};

std::string read(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Runs a shell command line in `dir` (stdout and stderr together); paths here have no quotes.
CliResult run_in(const fs::path& dir, const std::string& command) {
  const std::string line = "cd '" + dir.string() + "' && " + command + " 2>&1";
  FILE* pipe = popen(line.c_str(), "r");
  CliResult r;
  std::array<char, 4096> buffer{};
  while (fgets(buffer.data(), static_cast<int>(buffer.size()), pipe) != nullptr)
    r.output += buffer.data();
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

TEST(NewPlugin, RefusesAnUnknownKind) {
  const auto dir = scratch_directory("new_plugin_kind");
  const CliResult r = run_rumble({"new-plugin", "rock", "my_rock", (dir / "x").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("rumble: error: new-plugin: unknown kind 'rock'; KIND is soil, "
                                  "vehicle or coupler (e.g. rumble new-plugin soil my_soil)"));
  EXPECT_FALSE(fs::exists(dir / "x"));
}

TEST(NewPlugin, RefusesANameThatIsNotLowerSnakeCase) {
  const auto dir = scratch_directory("new_plugin_name");
  for (const std::string name : {"My_Soil", "my-soil", "2soil", "_soil", "soil_", "my__soil", ""}) {
    SCOPED_TRACE(name);
    const CliResult r = run_rumble({"new-plugin", "soil", name, (dir / "x").string()});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.output,
                HasSubstr("new-plugin: NAME '" + name +
                          "' is not a lower snake_case identifier; use lower-case letters, "
                          "digits and single '_' between words, starting with a letter (e.g. "
                          "my_soil)"));
    EXPECT_FALSE(fs::exists(dir / "x"));
  }
}

TEST(NewPlugin, NeverWritesIntoANonEmptyDirectoryOrOverAFile) {
  const auto dir = scratch_directory("new_plugin_existing");
  fs::create_directories(dir / "taken");
  std::ofstream(dir / "taken" / "CMakeLists.txt") << "mine\n";
  const CliResult r = run_rumble({"new-plugin", "soil", "my_soil", (dir / "taken").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("new-plugin: directory '" + (dir / "taken").string() +
                                  "' exists and is not empty; give a new DIR (default ./NAME) "
                                  "or empty it"));
  EXPECT_EQ(read(dir / "taken" / "CMakeLists.txt"), "mine\n");

  std::ofstream(dir / "file") << "mine\n";
  const CliResult f = run_rumble({"new-plugin", "soil", "my_soil", (dir / "file").string()});
  EXPECT_EQ(f.exit_code, 1);
  EXPECT_THAT(f.output, HasSubstr("new-plugin: '" + (dir / "file").string() +
                                  "' exists and is not a directory; give a new DIR (default "
                                  "./NAME)"));
}

TEST(NewPlugin, NeedsKindAndName) {
  for (const std::vector<std::string>& args : {std::vector<std::string>{"new-plugin"},
                                               {"new-plugin", "soil"},
                                               {"new-plugin", "soil", "a", "b", "c"}}) {
    const CliResult r = run_rumble(args);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_THAT(r.output, HasSubstr("new-plugin takes KIND NAME [DIR]; usage: rumble new-plugin "
                                    "soil|vehicle|coupler NAME [DIR] (e.g. rumble new-plugin "
                                    "soil my_soil)"));
  }
  EXPECT_THAT(run_rumble({"--help"}).output, HasSubstr("new-plugin KIND NAME [DIR]"));
}

// Every occurrence of the template's names is replaced, in file names and contents; the copy
// goes into an empty directory that exists, or a new one.
TEST(NewPlugin, ScaffoldsEveryKindWithTheTemplateNamesReplaced) {
  const auto dir = scratch_directory("new_plugin_kinds");
  fs::create_directories(dir / "soil");  // exists and is empty: accepted
  for (const std::string kind : {"soil", "vehicle", "coupler"}) {
    SCOPED_TRACE(kind);
    const std::string name = "acme_" + kind + "2";
    const CliResult r = run_rumble({"new-plugin", kind, name, (dir / kind).string()});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_THAT(r.output, HasSubstr("created " + kind + " plugin '" + name + "' in "));
    for (const std::string& file : std::vector<std::string>{"CMakeLists.txt", "README.md",
                                                            name + ".cpp", name + "_test.cpp"}) {
      ASSERT_TRUE(fs::exists(dir / kind / file)) << file;
    }
    for (const fs::directory_entry& e : fs::directory_iterator(dir / kind)) {
      const std::string text = read(e.path());
      for (const std::string& old : kTemplateNames) {
        EXPECT_EQ(e.path().filename().string().find(old), std::string::npos) << e.path();
        EXPECT_EQ(text.find(old), std::string::npos) << old << " left in " << e.path();
      }
    }
    const std::string camel =
        "Acme" + std::string(1, static_cast<char>(kind[0] - 'a' + 'A')) + kind.substr(1) + "2";
    const std::string source = read(dir / kind / (name + ".cpp"));
    EXPECT_THAT(source, HasSubstr("class " + camel + " final"));
    EXPECT_THAT(source, HasSubstr("RUMBLE_PLUGIN(\"" + name + "\", \"0.1.0\", " + camel + ")"));
    EXPECT_THAT(read(dir / kind / "CMakeLists.txt"), HasSubstr("add_test(NAME " + name + "_test"));
  }
}

TEST(NewPlugin, DirectoryDefaultsToTheName) {
  const auto dir = scratch_directory("new_plugin_default_dir");
  const CliResult r = run_in(dir, std::string(RUMBLE_TEST_EXE) + " new-plugin vehicle my_train");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir / "my_train" / "my_train.cpp"));
}

// The build copies what an install puts in share/rumble, so the build tree's rumble finds it the
// same way: a run with plots on calls the script from there (which then fails without matplotlib,
// or draws the plots).
TEST(ShareLookup, TheBuildTreeMirrorsTheInstall) {
  for (const char* file :
       {"plot_results.py", "plot_frf.py", "template/template_soil.cpp",
        "template_vehicle/template_vehicle.cpp", "template_coupler/template_coupler_test.cpp"}) {
    EXPECT_TRUE(fs::exists(kBuild / "share" / "rumble" / file)) << file;
  }
  const auto dir = scratch_directory("share_lookup_build_tree");
  nlohmann::json s = small_scenario();
  s["outputs"]["plots"] = true;
  const CliResult r = run_rumble({"run", write_scenario(dir, s).string(), "--no-progress"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string script = (kBuild / "share" / "rumble" / "plot_results.py").string();
  EXPECT_TRUE(fs::exists(dir / "results" / "contact_force.png") ||
              r.output.find("plots failed: " + script) != std::string::npos)
      << r.output;
}

// A rumble away from any share/rumble looks only next to itself and says so, with the fix.
TEST(ShareLookup, ACopiedBinaryLooksOnlyNextToItself) {
  const auto dir = scratch_directory("share_lookup_copied_binary");
  fs::create_directories(dir / "bin");
  fs::copy_file(RUMBLE_TEST_EXE, dir / "bin" / "rumble");
  const fs::path share = fs::weakly_canonical(dir) / "share" / "rumble";
  const std::string exe = (dir / "bin" / "rumble").string();

  const CliResult t = run_in(dir, exe + " new-plugin soil my_soil");
  EXPECT_EQ(t.exit_code, 3);
  EXPECT_THAT(t.output,
              HasSubstr("new-plugin: the soil template '" + (share / "template").string() +
                        "' does not exist; reinstall Rumble with its SDK (cmake "
                        "--install <build dir>), which puts the templates in "
                        "share/rumble"));
  EXPECT_FALSE(fs::exists(dir / "my_soil"));

  nlohmann::json s = small_scenario();
  s["outputs"]["plots"] = true;
  const CliResult p =
      run_in(dir, "RUMBLE_PLUGIN_PATH=" + std::string(RUMBLE_TEST_PLUGIN_DIR) + " " + exe +
                      " run " + write_scenario(dir, s).string() + " --no-progress");
  EXPECT_EQ(p.exit_code, 0) << p.output;
  EXPECT_THAT(p.output, HasSubstr("plots skipped: " + (share / "plot_results.py").string() +
                                  " not found (the plot scripts belong in share/rumble next to "
                                  "the bin/ holding rumble); reinstall Rumble with cmake "
                                  "--install, or rebuild it"));
}

}  // namespace
}  // namespace rumble::testing
