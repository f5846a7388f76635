// A study file (`rumble study FILE`, docs/study.md): a base scenario and the variations of it to
// run, as a Cartesian product of named axes and/or a list of explicit runs. Read and checked here;
// expanded into runs by expansion.hpp.
#pragma once

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "scenario/diagnostic.hpp"
#include "scenario/document.hpp"

namespace rumble::study {

inline constexpr int kStudyVersion = 1;
/// Most runs one study holds, axes' product and listed runs together (docs/study.md): each is a
/// process, a results folder and a line of the report; 1e4 is days of FEM runs.
inline constexpr double kMaxStudyRuns = 1e4;
/// Longest run name: a run's name is the name of its results folder, and no Linux file system
/// takes a longer one (NAME_MAX). A product run's name joins a value name of each axis.
inline constexpr std::size_t kMaxRunNameBytes = 255;

/// One value replaced in a run's scenario.
struct Patch {
  std::string pointer;   // into the scenario: "/soil/params/E"
  nlohmann::json value;  // what replaces the value there
  std::string source;    // JSON pointer of this entry in the study file
};

struct AxisValue {
  std::string name;  // part of the run names
  std::vector<Patch> patches;
};

struct Axis {
  std::string name;
  std::vector<AxisValue> values;  // in the file's order
};

struct ExplicitRun {
  std::string name;
  std::filesystem::path scenario;  // resolved; the study's scenario when the entry names none
  std::vector<Patch> set;
  nlohmann::ordered_json entry;  // the entry as written
  std::string source;            // "/runs/<i>"
};

struct StudyFile {
  std::filesystem::path path;
  std::string name, description;
  std::filesystem::path scenario;  // resolved against the study file's folder; "" when none
  std::filesystem::path output;    // resolved against the study file's folder
  std::string output_text;         // as written ("results/<stem>" when the file names none)
  std::vector<Axis> axes;
  std::vector<ExplicitRun> runs;
  std::optional<int> jobs;
};

/// The study's output folder when it lies outside the study file's folder (absolute, leaving it
/// with "..", or leading out of it through a symbolic link: scenario::outside_folder), the
/// finding at /output; `rumble study` allows it with --allow-outside-results. nullopt: inside.
std::optional<scenario::Diagnostic> output_outside_folder(const StudyFile& study);

/// A name that can be a directory: 1 to 100 of [A-Za-z0-9._-], starting with a letter or digit.
bool filesystem_safe(const std::string& name);

/// Checks the study in `doc` (parsed already) and returns it, or nullopt with every problem
/// found appended to `diagnostics` (JSON pointers into the study file, the value, the fix):
/// unknown keys, wrong types, empty axes, unsafe or duplicate names, product run names too long
/// for a folder, malformed pointers, scenario files that do not exist. Duplicate run names are
/// checked by expand().
std::optional<StudyFile> read_study(const scenario::Document& doc,
                                    std::vector<scenario::Diagnostic>& diagnostics);

}  // namespace rumble::study
