// `rumble run --set` and `rumble validate --set`: the value is used, recorded in summary.json,
// part of the results directory's identity, and every message about a bad --set.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_runner.hpp"

namespace rumble::testing {
namespace {

using ::testing::HasSubstr;

TEST(SetOption, RunUsesAndRecordsTheValues) {
  const auto dir = scratch_directory("set_run");
  const auto path = write_scenario(dir, small_scenario());
  const CliResult r = run_rumble({"run", path.string(), "--no-progress", "--set",
                                  "/soil/params/k=5e7", "--set=/coupling/type=jacobi"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto summary = read_json(dir / "results" / "summary.json");
  EXPECT_EQ(summary["scenario"]["soil"]["params"]["k"], 5e7);
  EXPECT_EQ(summary["scenario"]["coupling"]["type"], "jacobi");
  EXPECT_EQ(summary["overrides"],
            nlohmann::json::parse(R"([{"pointer": "/soil/params/k", "value": 5e7},
                                      {"pointer": "/coupling/type", "value": "jacobi"}])"));
  // A softer soil: a larger static footprint displacement than the file's k = 1e8 gives.
  const auto plain_dir = scratch_directory("set_run_plain");
  ASSERT_EQ(
      run_rumble({"run", write_scenario(plain_dir, small_scenario()).string(), "--no-progress"})
          .exit_code,
      0);
  const auto plain = read_json(plain_dir / "results" / "summary.json");
  EXPECT_EQ(plain["overrides"], nlohmann::json::array());
  std::vector<double> t, soft, stiff;
  read_csv(dir / "results" / "footprint_displacement.csv", t, soft);
  read_csv(plain_dir / "results" / "footprint_displacement.csv", t, stiff);
  double max_soft = 0.0, max_stiff = 0.0;
  for (const double x : soft) max_soft = std::max(max_soft, std::abs(x));
  for (const double x : stiff) max_stiff = std::max(max_stiff, std::abs(x));
  EXPECT_GT(max_soft, 1.5 * max_stiff);
}

TEST(SetOption, OtherValuesAreAnotherRunInTheResultsDirectory) {
  const auto dir = scratch_directory("set_identity");
  const auto path = write_scenario(dir, small_scenario());
  ASSERT_EQ(
      run_rumble({"run", path.string(), "--no-progress", "--set", "/soil/params/k=5e7"}).exit_code,
      0);
  // The same values again: the same run, replaced.
  const CliResult same =
      run_rumble({"run", path.string(), "--no-progress", "--set", "/soil/params/k=5e7"});
  EXPECT_EQ(same.exit_code, 0) << same.output;
  const CliResult other =
      run_rumble({"run", path.string(), "--no-progress", "--set", "/soil/params/k=6e7"});
  EXPECT_EQ(other.exit_code, 1) << other.output;
  EXPECT_THAT(other.output, HasSubstr("holds the results of another run of " +
                                      std::filesystem::canonical(path).string() +
                                      " (--set /soil/params/k=50000000.0, says "));
  EXPECT_THAT(other.output, HasSubstr("pass --overwrite"));
  const CliResult none = run_rumble({"run", path.string(), "--no-progress"});
  EXPECT_EQ(none.exit_code, 1) << none.output;
  EXPECT_EQ(run_rumble({"run", path.string(), "--no-progress", "--overwrite", "--set",
                        "/soil/params/k=6e7"})
                .exit_code,
            0);
}

TEST(SetOption, DiagnosticsSayTheValueWasSet) {
  const auto dir = scratch_directory("set_validate");
  const auto path = write_scenario(dir, small_scenario());
  const CliResult r = run_rumble(
      {"validate", path.string(), "--set", "/soil/params/k=-1", "--set", "/soil/parms/k=1"});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("/soil/params/k: must be in [10000, 1e+13]"));
  EXPECT_THAT(r.output, HasSubstr("got -1 (set by --set)"));
  EXPECT_THAT(r.output, HasSubstr("/soil/parms: unknown key"));
  const CliResult ok = run_rumble({"validate", path.string(), "--set", "/soil/params/k=2e8"});
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_THAT(ok.output, HasSubstr(": valid"));
}

TEST(SetOption, BadSetMessages) {
  const auto dir = scratch_directory("set_bad");
  const auto path = write_scenario(dir, small_scenario()).string();
  const auto error = [&](const std::string& command, const std::string& set) {
    const CliResult r = run_rumble({command, path, "--set", set});
    EXPECT_EQ(r.exit_code, 1) << r.output;
    return r.output;
  };
  EXPECT_THAT(error("validate", "soil"),
              HasSubstr("rumble: error: --set soil: expected POINTER=VALUE, e.g. --set "
                        "/soil/params/E=1.55e8 or --set /coupling/type=jacobi"));
  EXPECT_THAT(error("run", "soil/params/k=1"),
              HasSubstr("rumble: error: --set soil/params/k=1: \"soil/params/k\" is not a JSON "
                        "pointer: it starts with '/', e.g. /soil/params/E"));
  EXPECT_THAT(error("run", "/vehicles/2/speed=10"),
              HasSubstr("rumble: error: --set /vehicles/2/speed=10: /vehicles is an array (it has "
                        "1 element, index 0), which has no element \"2\"; an override replaces an "
                        "element but does not add one: add it in the scenario file"));
  EXPECT_THAT(error("validate", "/soil/type/x=1"),
              HasSubstr("rumble: error: --set /soil/type/x=1: /soil/type is a string, not an "
                        "object or array, so it has no member \"x\"; set /soil/type itself, or "
                        "correct the pointer"));
  EXPECT_THAT(error("validate", "/soil/params={\"k\":"),
              HasSubstr("the value is not valid JSON (parse error"));
  EXPECT_THAT(error("validate", "/name="), HasSubstr("no value after '='"));
  const CliResult missing = run_rumble({"validate", path, "--set"});
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_THAT(missing.output, HasSubstr("option --set needs a value"));
}

}  // namespace
}  // namespace rumble::testing
