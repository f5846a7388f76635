// Golden tests: every message shape, exactly as print_diagnostics writes it.
//
// tests/scenario/invalid/<case>.json is the input (absent for the file-not-found case) and
// <case>.expected the exact text output, with the file printed as the path relative to the
// source root. An expected file may start with directive lines
//   # requires: <kind> <type>[, <kind> <type>...]
// naming the in-tree plugins the case needs; the case is skipped, with that message, until they
// are built. <case>.expected.json, when present, is the JSON output of the same case.
// RUMBLE_UPDATE_GOLDEN=1 rewrites the expected files from the actual output (keeping the
// directives); review the diff before committing.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "scenario/check_file.hpp"
#include "scenario/scenario.hpp"
#include "test_support.hpp"

namespace rumble::scenario {
namespace {

namespace fs = std::filesystem;

fs::path invalid_dir() {
  return test::scenario_test_dir() / "invalid";
}

std::vector<std::string> case_names() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(invalid_dir(), ec)) {
    const std::string file = entry.path().filename().string();
    const std::string suffix = ".expected";
    if (file.size() > suffix.size() && file.substr(file.size() - suffix.size()) == suffix) {
      names.push_back(file.substr(0, file.size() - suffix.size()));
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

struct Expected {
  std::string directives;  // the "# ..." lines, kept when updating
  std::vector<test::Requirement> needs;
  std::string text;
};

std::optional<rumble_kind> kind_from(const std::string& name) {
  for (const rumble_kind k : {RUMBLE_KIND_VEHICLE, RUMBLE_KIND_SOIL, RUMBLE_KIND_COUPLER}) {
    if (name == kind_name(k)) return k;
  }
  return std::nullopt;
}

Expected read_expected(const fs::path& file) {
  Expected e;
  std::istringstream in(test::read_file(file));
  std::string line;
  std::ostringstream text;
  bool header = true;
  while (std::getline(in, line)) {
    if (header && line.rfind("# ", 0) == 0) {
      e.directives += line + "\n";
      const std::string key = "# requires: ";
      if (line.rfind(key, 0) != 0) continue;
      std::istringstream list(line.substr(key.size()));
      std::string item;
      while (std::getline(list, item, ',')) {
        std::istringstream words(item);
        std::string kind;
        std::string type;
        words >> kind >> type;
        const auto k = kind_from(kind);
        if (!k || type.empty())
          throw std::runtime_error("bad directive in " + file.string() + ": " + line);
        e.needs.push_back({*k, type});
      }
      continue;
    }
    header = false;
    text << line << "\n";
  }
  e.text = text.str();
  return e;
}

/// What `rumble validate` would print for the case (the whole check: schema, relations, run
/// size, components), with the file named relative to the source root.
std::string run_case(const std::string& name, Format format) {
  const fs::path relative = fs::path("tests") / "scenario" / "invalid" / (name + ".json");
  PluginRegistry registry = test::golden_registry();
  std::vector<Override> overrides;
  const CheckedScenario checked =
      check_scenario_file(test::source_dir() / relative, overrides, registry);
  std::ostringstream os;
  print_diagnostics(os, checked.doc ? &*checked.doc : nullptr, relative, checked.diagnostics,
                    format);
  return os.str();
}

bool updating() {
  const char* v = std::getenv("RUMBLE_UPDATE_GOLDEN");
  return v != nullptr && std::string(v) == "1";
}

class Golden : public ::testing::TestWithParam<std::string> {};

TEST_P(Golden, TextOutputMatchesTheExpectedFile) {
  const std::string name = GetParam();
  const fs::path expected_file = invalid_dir() / (name + ".expected");
  const Expected expected = read_expected(expected_file);
  if (const auto missing = test::missing_plugins(test::golden_registry(), expected.needs);
      !missing.empty()) {
    GTEST_SKIP() << name << " " << missing;
  }
  const std::string actual = run_case(name, Format::kText);
  if (updating()) std::ofstream(expected_file, std::ios::binary) << expected.directives << actual;
  EXPECT_EQ(actual, expected.text) << "case " << name;
  EXPECT_FALSE(actual.empty()) << "an invalid case must produce diagnostics";

  const fs::path json_file = invalid_dir() / (name + ".expected.json");
  if (fs::exists(json_file)) {
    const std::string actual_json = run_case(name, Format::kJson);
    if (updating()) std::ofstream(json_file, std::ios::binary) << actual_json;
    EXPECT_EQ(actual_json, test::read_file(json_file)) << "case " << name << " (JSON)";
  }
}

TEST(ScenarioGoldenCases, EveryMessageShapeHasACase) {
  const auto names = case_names();
  for (const char* needed :
       {"file_not_found", "parse_trailing_comma", "missing_required_key", "wrong_type",
        "out_of_range_exclusive", "out_of_range_inclusive", "enum_violation",
        "unknown_key_did_you_mean", "unknown_type_did_you_mean", "plugin_params_violation",
        "multiple_errors", "unevenness_variant_wrong_key", "duplicate_key",
        "run_size_too_many_steps", "sleepers_count_too_large", "rail_too_short_for_run"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), needed), names.end()) << needed;
  }
  bool has_json = false;
  for (const auto& n : names) has_json |= fs::exists(invalid_dir() / (n + ".expected.json"));
  EXPECT_TRUE(has_json) << "one case must pin the JSON format";
}

INSTANTIATE_TEST_SUITE_P(Scenario, Golden, ::testing::ValuesIn(case_names()),
                         [](const ::testing::TestParamInfo<std::string>& param_info) {
                           return param_info.param;
                         });

}  // namespace
}  // namespace rumble::scenario
