#include "scenario/validate.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/errors.hpp"
#include "plugin/manifest.hpp"
#include "plugin/registry.hpp"
#include "scenario/report.hpp"
#include "test_support.hpp"

namespace rumble::scenario {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

Document minimal_document() {
  std::vector<Diagnostic> diags;
  auto doc = load_document(test::scenario_test_dir() / "valid" / "minimal.json", diags);
  if (!doc) throw std::runtime_error("minimal.json does not parse");
  return *doc;
}

Document from_json(const json& j) {
  std::vector<Diagnostic> diags;
  auto doc = parse_document("edited.json", j.dump(2), diags);
  if (!doc) throw std::runtime_error("does not parse");
  return *doc;
}

std::string text_of(const Document& doc, const std::vector<Diagnostic>& diags) {
  std::ostringstream os;
  print_diagnostics(os, &doc, doc.path, diags, Format::kText);
  return os.str();
}

// A library known from its manifest is loaded when a scenario uses one of its types; one that
// cannot be (here: it differs from its manifest) is reported at the type, not at the run.
TEST(ScenarioValidate, ATypesLibraryThatDoesNotLoadIsReportedAtTheType) {
  // (one per process: the dev and sanitized suites may run side by side)
  const fs::path dir =
      fs::temp_directory_path() / ("rumble_validate_unloadable_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path winkler = dir / "winkler.so";
  fs::copy_file(fs::path(RUMBLE_TEST_PLUGIN_DIR) / "winkler.so", winkler);
  {
    PluginRegistry eager(PluginRegistry::Manifests::kIgnore);
    eager.load_library(winkler);
    json manifest = json::parse(manifest_text(*eager.libraries().front(), eager.types()));
    manifest["types"][0]["summary"] = "an older build's";
    std::ofstream(manifest_path(winkler)) << manifest.dump();
  }
  PluginRegistry registry;
  for (const char* other : {"single_wheel.so", "gauss_seidel.so"})
    registry.load_library(fs::path(RUMBLE_TEST_PLUGIN_DIR) / other);
  registry.load_library(winkler);
  Document doc = minimal_document();
  const auto diags = validate(doc, registry);
  const std::string text = text_of(doc, diags);
  ASSERT_EQ(diags.size(), 1u) << text;
  EXPECT_EQ(diags[0].pointer, "/soil/type");
  EXPECT_NE(text.find("not what its manifest"), std::string::npos) << text;
  EXPECT_NE(text.find("its summary differs"), std::string::npos) << text;
  EXPECT_NE(text.find("fix or rebuild the plugin; `rumble plugins` lists what loads"),
            std::string::npos)
      << text;
  fs::remove_all(dir);
}

TEST(ScenarioValidate, MinimalScenarioIsValidAndGetsItsDefaults) {
  const auto& registry = test::golden_registry();
  if (const auto missing = test::missing_plugins(registry, test::minimal_needs());
      !missing.empty()) {
    GTEST_SKIP() << missing;
  }
  Document doc = minimal_document();
  const auto diags = validate(doc, registry);
  EXPECT_TRUE(diags.empty()) << text_of(doc, diags);
  const json& j = doc.json;
  // Engine defaults, nested objects included.
  EXPECT_EQ(j["track"]["rail"]["elements_per_bay"], 4);
  EXPECT_EQ(j["track"]["rail"]["overhang_bays"], 1);
  EXPECT_EQ(j["track"]["contact"]["E"], 2.1e11);
  EXPECT_EQ(j["track"]["contact"]["nu"], 0.3);
  EXPECT_FALSE(j["track"]["contact"].contains("hertz_constant"));  // optional, no default
  EXPECT_EQ(j["track"]["integrator"]["gamma"], 0.5);
  EXPECT_EQ(j["track"]["damping"]["rayleigh_beta"], 0);
  EXPECT_EQ(j["outputs"]["every"], 1);
  EXPECT_EQ(j["outputs"]["plots"], true);
  EXPECT_EQ(j["outputs"]["receivers"], json::array());
  EXPECT_EQ(j["plugins"], json::array());
  EXPECT_EQ(j["vehicles"][0]["name"], "vehicle0");
  // Plugin defaults.
  EXPECT_EQ(j["vehicles"][0]["params"]["wheel_radius"], 0.46);
  EXPECT_EQ(j["coupling"]["params"]["order"], "track_first");

  // Validating the filled document again changes nothing.
  const json filled = doc.json;
  EXPECT_TRUE(validate(doc, registry).empty());
  EXPECT_EQ(doc.json, filled);
}

TEST(ScenarioValidate, AbsentUnevennessDefaultsToNoneAndVariantDefaultsAreFilled) {
  const auto& registry = test::golden_registry();
  if (const auto missing = test::missing_plugins(registry, test::minimal_needs());
      !missing.empty()) {
    GTEST_SKIP() << missing;
  }
  json j = minimal_document().json;
  j["track"].erase("unevenness");
  Document doc = from_json(j);
  EXPECT_TRUE(validate(doc, registry).empty());
  EXPECT_EQ(doc.json["track"]["unevenness"], json::parse(R"({"type": "none"})"));

  j["track"]["unevenness"] =
      json::parse(R"({"type": "wheel_flat", "length": 0.05, "depth": 1e-4})");
  Document flat = from_json(j);
  EXPECT_TRUE(validate(flat, registry).empty());
  EXPECT_EQ(flat.json["track"]["unevenness"]["wheel"], 0);
}

TEST(ScenarioValidate, TheSchemaAloneRefusesBadUnevennessValues) {
  // The track reads /track/unevenness as validated (track_spec/unevenness_spec.hpp) and checks
  // only the relations the schema cannot state; every value's type and range is the schema's.
  const auto& registry = test::golden_registry();
  if (const auto missing = test::missing_plugins(registry, test::minimal_needs());
      !missing.empty()) {
    GTEST_SKIP() << missing;
  }
  const std::vector<std::pair<const char*, const char*>> cases = {
      {R"({"type": "dip", "position": 1, "length": 0.3})", "/track/unevenness"},
      {R"({"type": "bump", "position": 1, "length": 0, "height": 1e-3})",
       "/track/unevenness/length"},
      {R"({"type": "dip", "position": "a", "length": 1, "depth": 1e-3})",
       "/track/unevenness/position"},
      {R"({"type": "wheel_flat", "length": 0.05, "depth": -1e-4})", "/track/unevenness/depth"},
      {R"({"type": "random", "class": "FRA7", "seed": 1, "wavelength_min": 1,
           "wavelength_max": 30})",
       "/track/unevenness/class"},
      {R"({"type": "random", "class": "FRA1", "seed": -1, "wavelength_min": 1,
           "wavelength_max": 30})",
       "/track/unevenness/seed"}};
  for (const auto& [unevenness, pointer] : cases) {
    json j = minimal_document().json;
    j["track"]["unevenness"] = json::parse(unevenness);
    Document doc = from_json(j);
    const auto diags = validate(doc, registry);
    ASSERT_FALSE(diags.empty()) << unevenness << " passed";
    EXPECT_EQ(diags.front().pointer, pointer) << unevenness << ": " << text_of(doc, diags);
  }
}

TEST(ScenarioValidate, ErrorsAreCollectedFromEverySourceAndSortedByPosition) {
  // No plugins at all: the three component types are unknown, and the engine's rules still run.
  const PluginRegistry empty;
  json j = minimal_document().json;
  j["time"]["macro_step"] = 0.1;  // > end
  j["track"]["sleepers"]["count"] = 2;
  Document doc = from_json(j);  // keys now in alphabetical order
  const auto diags = validate(doc, empty);
  std::vector<std::string> lines;
  for (const Diagnostic& d : diags) lines.push_back(d.pointer + ": " + d.message + " | " + d.hint);
  EXPECT_EQ(lines,
            (std::vector<std::string>{
                "/coupling/type: unknown coupler type \"gauss_seidel\" | no coupler plugins are "
                "loaded; list the library in /plugins or in RUMBLE_PLUGIN_PATH",
                "/soil/type: unknown soil type \"winkler\" | no soil plugins are loaded; list the "
                "library in /plugins or in RUMBLE_PLUGIN_PATH",
                "/time/macro_step: must be <= /time/end (0.05), got 0.1 | the coupling step cannot "
                "be longer than the whole run",
                "/track/sleepers/count: must be in [3, 100000], got 2 | number of sleepers; [3, "
                "100000]: a rail needs supports on both sides of a wheel; 100000 is 60 km at 0.6 m",
                "/vehicles/0/type: unknown vehicle type \"single_wheel\" | no vehicle plugins are "
                "loaded; list the library in /plugins or in RUMBLE_PLUGIN_PATH"}));
  for (std::size_t i = 1; i < diags.size(); ++i) {
    EXPECT_LT(std::pair(diags[i - 1].line, diags[i - 1].column),
              std::pair(diags[i].line, diags[i].column));
  }
}

TEST(ScenarioValidate, ATypeOfAnotherKindIsNamedAsSuch) {
  const auto& registry = test::golden_registry();
  if (registry.find(RUMBLE_KIND_VEHICLE, "single_wheel") == nullptr)
    GTEST_SKIP() << "no single_wheel";
  json j = minimal_document().json;
  j["soil"]["type"] = "single_wheel";
  Document doc = from_json(j);
  bool found = false;
  for (const Diagnostic& d : validate(doc, registry)) {
    if (d.pointer != "/soil/type") continue;
    found = true;
    EXPECT_EQ(d.message, "unknown soil type \"single_wheel\"");
    EXPECT_EQ(d.hint.rfind("\"single_wheel\" is a vehicle type; ", 0), 0u) << d.hint;
  }
  EXPECT_TRUE(found);
}

TEST(ScenarioValidate, TooManyErrorsAreCutWithACount) {
  const PluginRegistry empty;
  json j = minimal_document().json;
  j["outputs"]["receivers"] = std::vector<double>(150, -1.0);
  Document doc = from_json(j);
  const auto diags = validate(doc, empty);
  ASSERT_EQ(diags.size(), kMaxDiagnostics + 1);
  EXPECT_EQ(diags.back().message, "53 more errors not shown");
}

TEST(ScenarioValidate, HugeAndDeepDocumentsAreRefusedNotWalked) {
  const PluginRegistry empty;
  Document huge;
  huge.json = json::parse(R"({"description": ""})");
  huge.json["x"] = std::vector<int>(kMaxValues + 1, 0);
  auto diags = validate(huge, empty);
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].message.rfind("too many values", 0), 0u) << diags[0].message;

  Document deep;  // built by hand, so load_document's depth check never saw it
  json* cursor = &deep.json;
  for (int i = 0; i < 1000; ++i) cursor = &((*cursor)["a"] = json::object());
  diags = validate(deep, empty);
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].message, "nesting is too deep (more than 256 levels)");
}

TEST(ScenarioValidate, MakeDiagnosticFindsTheValueOrItsNearestAncestor) {
  const Document doc = minimal_document();
  const Diagnostic d = make_diagnostic(doc, "/track/sleepers/spacing", "too wide", "narrow it");
  EXPECT_EQ(d.line, 17u);
  EXPECT_EQ(d.column, 18u);
  EXPECT_EQ(d.hint, "narrow it");
  EXPECT_EQ(d.severity, Diagnostic::Severity::kError);
  // Not in the text (a default): the enclosing object.
  const Diagnostic filled =
      make_diagnostic(doc, "/track/rail/elements_per_bay", "x", "", Diagnostic::Severity::kWarning);
  EXPECT_EQ(filled.line, 21u);
  EXPECT_EQ(filled.column, 13u);
  EXPECT_EQ(filled.severity, Diagnostic::Severity::kWarning);
}

class ScenarioPlugins : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("rumble_scenario_plugins_" +
            std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_ / "libs");
    fs::copy_file(SCENARIO_TEST_BAD_PLUGIN, dir_ / "libs" / "bad_plugin.so",
                  fs::copy_options::overwrite_existing);
  }
  void TearDown() override { fs::remove_all(dir_); }

  Document write_scenario(const json& plugins, const std::string& soil_type) {
    json j = minimal_document().json;
    j["plugins"] = plugins;
    j["soil"]["type"] = soil_type;
    const fs::path file = dir_ / "scenario.json";
    std::ofstream(file) << j.dump(2);
    std::vector<Diagnostic> diags;
    auto doc = load_document(file, diags);
    if (!doc) throw std::runtime_error("cannot load");
    return *doc;
  }

  fs::path dir_;
};

TEST_F(ScenarioPlugins, AreLoadedRelativeToTheScenarioFile) {
  Document doc = write_scenario(json::array({"libs/bad_plugin.so"}), "no_schema_soil");
  PluginRegistry registry;
  load_scenario_plugins(doc, registry);
  EXPECT_NE(registry.find(RUMBLE_KIND_SOIL, "no_schema_soil"), nullptr);
}

TEST_F(ScenarioPlugins, AMissingLibraryNamesTheFileAndTheEntry) {
  Document doc = write_scenario(json::array({"libs/bad_plugin.so", "libs/missing.so"}), "x");
  PluginRegistry registry;
  try {
    load_scenario_plugins(doc, registry);
    FAIL() << "no PluginLoadError";
  } catch (const PluginLoadError& e) {
    const std::string prefix = doc.path.string() + ": /plugins/1: ";
    EXPECT_EQ(std::string(e.what()).rfind(prefix, 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("missing.so"), std::string::npos) << e.what();
  }
}

TEST_F(ScenarioPlugins, ATypeWithoutASchemaIsAPluginBugNamingTheLibrary) {
  for (const char* type : {"no_schema_soil", "bad_schema_soil"}) {
    Document doc = write_scenario(json::array({"libs/bad_plugin.so"}), type);
    PluginRegistry registry;
    load_scenario_plugins(doc, registry);
    bool found = false;
    for (const Diagnostic& d : validate(doc, registry)) {
      if (d.pointer != "/soil/type") continue;
      found = true;
      EXPECT_NE(d.message.find("(a bug in plugin " +
                               fs::canonical(dir_ / "libs" / "bad_plugin.so").string()),
                std::string::npos)
          << d.message;
      EXPECT_NE(d.message.find(std::string("soil type \"") + type + "\""), std::string::npos);
      EXPECT_GT(d.line, 0u);
    }
    EXPECT_TRUE(found) << type;
  }
}

}  // namespace
}  // namespace rumble::scenario
