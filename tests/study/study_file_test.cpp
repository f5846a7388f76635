// Study files: what is read, and every message about what is wrong in one.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "study_test_support.hpp"

namespace rumble::study {
namespace {

using ::testing::ElementsAre;
using testing::read;
using testing::study_folder;

TEST(StudyFile, ReadsEverything) {
  const auto r = read(R"({"study_version": 1, "name": "paper", "description": "d",
    "scenario": "base.json", "output": "out/s", "jobs": 3,
    "axes": [{"name": "soil", "values": {"soft": {"/soil/params/E": 1e7, "/a~1b": "x"},
                                         "medium": {}}}],
    "runs": [{"name": "fine", "scenario": "other.json", "set": {"/time/macro_step": 1e-4}},
             {"name": "plain"}]})");
  ASSERT_TRUE(r.study) << ::testing::PrintToString(r.problems);
  const StudyFile& s = *r.study;
  EXPECT_EQ(s.name, "paper");
  EXPECT_EQ(s.description, "d");
  EXPECT_EQ(s.scenario, study_folder() / "base.json");
  EXPECT_EQ(s.output, study_folder() / "out/s");
  EXPECT_EQ(s.jobs, 3);
  ASSERT_EQ(s.axes.size(), 1u);
  ASSERT_EQ(s.axes[0].values.size(), 2u);
  EXPECT_EQ(s.axes[0].values[0].name, "soft");  // the file's order, not sorted
  EXPECT_EQ(s.axes[0].values[1].name, "medium");
  ASSERT_EQ(s.axes[0].values[0].patches.size(), 2u);
  EXPECT_EQ(s.axes[0].values[0].patches[0].pointer, "/soil/params/E");
  EXPECT_EQ(s.axes[0].values[0].patches[0].value, 1e7);
  EXPECT_EQ(s.axes[0].values[0].patches[0].source, "/axes/0/values/soft/~1soil~1params~1E");
  EXPECT_EQ(s.axes[0].values[0].patches[1].pointer, "/a~1b");
  ASSERT_EQ(s.runs.size(), 2u);
  EXPECT_EQ(s.runs[0].scenario, study_folder() / "other.json");
  EXPECT_EQ(s.runs[0].set.at(0).source, "/runs/0/set/~1time~1macro_step");
  EXPECT_EQ(s.runs[1].scenario, study_folder() / "base.json");
}

TEST(StudyFile, Defaults) {
  const auto r = read(R"({"study_version": 1, "scenario": "base.json", "runs": [{"name": "a"}]})");
  ASSERT_TRUE(r.study);
  EXPECT_EQ(r.study->name, "study");
  EXPECT_EQ(r.study->output, study_folder() / "results/study");
  EXPECT_FALSE(r.study->jobs);
}

TEST(StudyFile, TopLevelMessages) {
  EXPECT_THAT(read("[1]").problems,
              ElementsAre(": a study file is one JSON object, got [1] | e.g. {\"study_version\": "
                          "1, \"scenario\": \"base.json\", \"axes\": [...]}"));
  EXPECT_THAT(read(R"({"scenario": "base.json", "runs": [{"name": "a"}]})").problems,
              ElementsAre(": missing \"study_version\" | add \"study_version\": 1 at the top"));
  EXPECT_THAT(
      read(R"({"study_version": 2, "scenario": "base.json", "runs": [{"name": "a"}]})").problems,
      ElementsAre("/study_version: must be 1, got 2 | this rumble reads study files of version 1"));
  EXPECT_THAT(
      read(R"({"study_version": 1, "scenario": "base.json", "axis": [], "runs": [{"name": "a"}]})")
          .problems,
      ElementsAre("/axis: unknown key 'axis' in a study | did you mean \"axes\"? keys of a study: "
                  "study_version, name, description, scenario, output, axes, runs, jobs"));
  EXPECT_THAT(read(R"({"study_version": 1, "name": 5, "scenario": "base.json",
                      "runs": [{"name": "a"}]})")
                  .problems,
              ElementsAre("/name: must be a non-empty string, got 5 | a short title of the study"));
  EXPECT_THAT(read(R"({"study_version": 1, "jobs": 0, "scenario": "base.json",
                      "runs": [{"name": "a"}]})")
                  .problems,
              ElementsAre("/jobs: must be an integer from 1 to 1024, got 0 | the number of runs "
                          "at once; leave it out to use half the cores"));
  EXPECT_THAT(
      read(R"({"study_version": 1, "scenario": "missing.json", "runs": [{"name": "a"}]})").problems,
      ElementsAre("/scenario: scenario file " +
                  (study_folder() / "missing.json").lexically_normal().string() +
                  " not found | paths are relative to the study file's folder (" +
                  study_folder().string() + ")"));
  EXPECT_THAT(read(R"({"study_version": 1, "scenario": "base.json"})").problems,
              ElementsAre(": the study has no runs | add \"axes\" (the product of their values is "
                          "run) or \"runs\" (a list), or both"));
}

TEST(StudyFile, AxisMessages) {
  const auto with_axes = [](const std::string& axes) {
    return read(R"({"study_version": 1, "scenario": "base.json", "axes": )" + axes + "}").problems;
  };
  EXPECT_THAT(with_axes("[]"),
              ElementsAre("/axes: must be a non-empty array of axes, got [] | e.g. [{\"name\": "
                          "\"soil\", \"values\": {\"soft\": {\"/soil/params/E\": 1e7}}}]; leave "
                          "\"axes\" out to list only \"runs\""));
  EXPECT_THAT(
      read(R"({"study_version": 1, "axes": [{"name": "a", "values": {"x": {}}}]})").problems,
      ElementsAre("/axes: axes vary the base scenario, and the study names none | add "
                  "\"scenario\": \"FILE.json\" (relative to the study file)"));
  EXPECT_THAT(with_axes("[3]"),
              ElementsAre("/axes/0: an axis must be an object {\"name\", \"values\"}, got 3 | "));
  EXPECT_THAT(with_axes(R"([{"name": "a", "value": {}, "values": {"x": {}}}])"),
              ElementsAre("/axes/0/value: unknown key 'value' in an axis | did you mean "
                          "\"values\"? keys of an axis: name, values"));
  EXPECT_THAT(with_axes(R"([{"values": {"x": {}}}])"),
              ElementsAre("/axes/0: missing \"name\" | e.g. \"name\": \"soil\""));
  EXPECT_THAT(with_axes(R"([{"name": "my soil", "values": {"x": {}}}])"),
              ElementsAre("/axes/0/name: axis name 'my soil' cannot name a directory | use 1 to "
                          "100 letters, digits, '.', '_' or '-', starting with a letter or digit"));
  EXPECT_THAT(
      with_axes(R"([{"name": "a", "values": {"x": {}}}, {"name": "a", "values": {"y": {}}}])"),
      ElementsAre("/axes/1/name: axis name 'a' is used twice | give each axis its own name"));
  EXPECT_THAT(with_axes(R"([{"name": "a"}])"),
              ElementsAre("/axes/0: missing \"values\" | e.g. \"values\": {\"soft\": "
                          "{\"/soil/params/E\": 1e7}, \"stiff\": {...}}"));
  EXPECT_THAT(with_axes(R"([{"name": "a", "values": {}}])"),
              ElementsAre("/axes/0/values: must be an object with at least one named value, got "
                          "{} | e.g. {\"soft\": {\"/soil/params/E\": 1e7}, \"stiff\": "
                          "{\"/soil/params/E\": 7.5e8}}"));
  EXPECT_THAT(with_axes(R"([{"name": "a", "values": {"../x": {}}}])"),
              ElementsAre("/axes/0/values/..~1x: value name '../x' cannot name a directory | use "
                          "1 to 100 letters, digits, '.', '_' or '-', starting with a letter or "
                          "digit"));
  EXPECT_THAT(with_axes(R"([{"name": "a", "values": {"x": 1e7}}])"),
              ElementsAre("/axes/0/values/x: an axis value must be an object of JSON pointers and "
                          "values, got 1e+07 | e.g. {\"/soil/params/E\": 1.55e8, "
                          "\"/coupling/type\": \"jacobi\"}"));
  EXPECT_THAT(with_axes(R"([{"name": "a", "values": {"x": {"soil/params/E": 1}}}])"),
              ElementsAre("/axes/0/values/x/soil~1params~1E: \"soil/params/E\" is not a JSON "
                          "pointer: it starts with '/', e.g. /soil/params/E | a key here names "
                          "the scenario value to replace"));
}

// 8 axes of 20 values were 2.6e10 runs: --dry-run died of std::bad_alloc expanding them
// (issue #30 item 2). The product is counted first.
TEST(StudyFile, AxesThatMultiplyBeyondTheLimitAreRefusedUnexpanded) {
  std::string axes = "[";
  for (int a = 0; a < 8; ++a) {
    axes += std::string(a ? ", " : "") + "{\"name\": \"a" + std::to_string(a) + "\", \"values\": {";
    for (int v = 0; v < 20; ++v)
      axes += std::string(v ? ", " : "") + "\"v" + std::to_string(v) + "\": {\"/time/end\": 0.1}";
    axes += "}}";
  }
  axes += "]";
  EXPECT_THAT(
      read(R"({"study_version": 1, "scenario": "base.json", "axes": )" + axes + "}").problems,
      ElementsAre("/axes: the study has 2.56e+10 runs (20 x 20 x 20 x 20 x 20 x 20 x 20 x 20 from "
                  "the axes), more than the 10000 a study holds | remove axes or values, or "
                  "split the study into several"));
}

// A product run's name joins a value name of each axis and names its results folder: three axes
// of 100-character value names passed --dry-run, and `rumble study` stopped at the first such run
// ("cannot create the results directory ...: File name too long") after the runs before it had
// run. Found by the study fuzz target's run-name property on its seed
// tests/fuzz/corpus/study/long_names.json.
TEST(StudyFile, ProductRunNamesTooLongForAFolderAreRefused) {
  const auto axis = [](const std::string& name, char c, std::size_t n) {
    return "{\"name\": \"" + name + "\", \"values\": {\"short\": {}, \"" + std::string(n, c) +
           "\": {}}}";
  };
  EXPECT_THAT(
      read(R"({"study_version": 1, "scenario": "base.json", "axes": [)" + axis("a", 'a', 100) +
           ", " + axis("b", 'b', 100) + ", " + axis("c", 'c', 100) + "]}")
          .problems,
      ElementsAre("/axes: the axes' product has run names of up to 302 characters (the "
                  "longest value name of each axis, 100 + 100 + 100, joined by '-'), more "
                  "than the 255 a results folder's name may have | shorten the value "
                  "names, or use fewer axes"));
  // 100 + 100 + 53 and the two dashes: 255, the longest a folder's name may be.
  EXPECT_TRUE(read(R"({"study_version": 1, "scenario": "base.json", "axes": [)" +
                   axis("a", 'a', 100) + ", " + axis("b", 'b', 100) + ", " + axis("c", 'c', 53) +
                   "]}")
                  .study);
}

TEST(StudyFile, RunMessages) {
  const auto with_runs = [](const std::string& runs) {
    return read(R"({"study_version": 1, "scenario": "base.json", "runs": )" + runs + "}").problems;
  };
  EXPECT_THAT(with_runs("{}"),
              ElementsAre("/runs: must be a non-empty array of runs, got {} | e.g. [{\"name\": "
                          "\"fine-step\", \"set\": {\"/time/macro_step\": 1e-4}}]; leave \"runs\" "
                          "out to run only the product of the axes"));
  EXPECT_THAT(with_runs("[\"a\"]"),
              ElementsAre("/runs/0: a run must be an object {\"name\", \"scenario\", \"set\"}, got "
                          "\"a\" | "));
  EXPECT_THAT(with_runs(R"([{"name": "a", "sett": {}}])"),
              ElementsAre("/runs/0/sett: unknown key 'sett' in a run | did you mean \"set\"? keys "
                          "of a run: name, scenario, set"));
  EXPECT_THAT(with_runs(R"([{"set": {}}])"),
              ElementsAre("/runs/0: missing \"name\" | e.g. \"name\": \"soft-fine-step\""));
  EXPECT_THAT(with_runs(R"([{"name": ".hidden"}])"),
              ElementsAre("/runs/0/name: run name '.hidden' cannot name a directory | use 1 to "
                          "100 letters, digits, '.', '_' or '-', starting with a letter or digit"));
  EXPECT_THAT(with_runs(R"([{"name": "a", "scenario": "nope.json"}])"),
              ElementsAre("/runs/0/scenario: scenario file " +
                          (study_folder() / "nope.json").lexically_normal().string() +
                          " not found | paths are relative to the study file's folder (" +
                          study_folder().string() + ")"));
  EXPECT_THAT(read(R"({"study_version": 1, "runs": [{"name": "a"}]})").problems,
              ElementsAre("/runs/0: this run names no scenario, and the study has no base "
                          "scenario | add \"scenario\": \"FILE.json\" to the run or to the study"));
  EXPECT_THAT(with_runs(R"([{"name": "a", "set": ["/x", 1]}])"),
              ElementsAre("/runs/0/set: \"set\" must be an object of JSON pointers and values, got "
                          "[\"/x\",1] | e.g. {\"/soil/params/E\": 1.55e8, \"/coupling/type\": "
                          "\"jacobi\"}"));
  EXPECT_THAT(with_runs(R"([{"name": "a", "set": {"": 1}}])"),
              ElementsAre("/runs/0/set/: the pointer is empty; name the value to replace, e.g. "
                          "/soil/params/E (the whole scenario cannot be replaced) | a key here "
                          "names the scenario value to replace"));
}

TEST(StudyFile, AllProblemsAtOnce) {
  const auto r = read(R"({"study_version": 3, "jobs": "x", "axes": [], "runs": []})");
  EXPECT_FALSE(r.study);
  EXPECT_EQ(r.problems.size(), 4u) << ::testing::PrintToString(r.problems);
}

// The study's results stay inside its folder unless the command line says otherwise (issue 30):
// "output" absolute, leaving with "..", or leading out through a symbolic link is refused.
TEST(StudyFile, AnOutputOutsideItsFolder) {
  const std::filesystem::path dir = study_folder();
  std::ofstream(dir / "study.json") << "{}\n";  // a file in a folder, as `rumble study` reads
  std::filesystem::remove_all(dir / "link");
  std::filesystem::create_directory_symlink("/tmp", dir / "link");
  const auto outside = [](const std::string& output) -> std::string {
    const auto r = read(R"({"study_version": 1, "scenario": "base.json", "output": )" +
                        nlohmann::json(output).dump() + R"(, "runs": [{"name": "a"}]})");
    if (!r.study) return ::testing::PrintToString(r.problems);
    const auto d = output_outside_folder(*r.study);
    return d ? d->pointer + ": " + d->message + " | " + d->hint : "inside";
  };
  const std::string hint =
      " | results go inside the study file's folder unless the command line says otherwise: "
      "pass --allow-outside-results to write to ";
  EXPECT_EQ(outside("/etc"), "/output: \"/etc\" is an absolute path" + hint + "/etc");
  EXPECT_EQ(outside("../.."), "/output: \"../..\" leaves the study file's folder " + dir.string() +
                                  " (it is " + (dir / "../..").lexically_normal().string() + ")" +
                                  hint + (dir / "../..").lexically_normal().string());
  const std::filesystem::path real = std::filesystem::canonical(dir);
  const std::filesystem::path tmp = std::filesystem::canonical("/tmp");
  EXPECT_EQ(outside("link/x"), "/output: \"link/x\" leads out of the study file's folder " +
                                   dir.string() + " through the symbolic link " +
                                   (real / "link").string() + " (it is " + (tmp / "x").string() +
                                   ")" + hint + (tmp / "x").string());
  EXPECT_EQ(outside("out/s"), "inside");
  EXPECT_EQ(outside("out/../results"), "inside");
  std::filesystem::remove(dir / "link");
}

TEST(FilesystemSafe, Names) {
  for (const char* ok : {"a", "soft-gs-0.1ms", "A_1", "0.1ms"}) EXPECT_TRUE(filesystem_safe(ok));
  for (const char* bad : {"", ".", "..", "-a", "a b", "a/b", "é", "_a"})
    EXPECT_FALSE(filesystem_safe(bad)) << bad;
  EXPECT_FALSE(filesystem_safe(std::string(101, 'a')));
}

}  // namespace
}  // namespace rumble::study
