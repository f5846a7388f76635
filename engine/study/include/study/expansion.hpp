// The runs of a study: the Cartesian product of its axes (first axis slowest, names joined by
// "-", patches applied in axis order), then its explicit runs. docs/study.md.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scenario/diagnostic.hpp"
#include "scenario/overrides.hpp"
#include "study/study_file.hpp"

namespace rumble::study {

struct PlannedRun {
  std::string name;
  std::filesystem::path scenario;  // the scenario file it varies
  std::vector<Patch> patches;      // applied in this order
  /// {"axis": "value name", ...} in axis order; empty for an explicit run.
  nlohmann::ordered_json axis_values = nlohmann::ordered_json::object();
  /// What the study file says of this run: the explicit run's entry, or the axis values with
  /// their patches (part of the run's key).
  nlohmann::ordered_json entry;
  std::string source;  // JSON pointer of the run in the study file ("" for a product run)
};

/// Every run of the study, product runs first. Two runs with one name are reported (at the
/// second one's place in the file) and the result is then empty.
std::vector<PlannedRun> expand(const StudyFile& study,
                               std::vector<scenario::Diagnostic>& diagnostics);

/// The patches as overrides of the run's scenario, labelled for messages with the study file
/// and the patch's place in it.
std::vector<scenario::Override> overrides(const PlannedRun& run,
                                          const std::filesystem::path& study_file);

}  // namespace rumble::study
