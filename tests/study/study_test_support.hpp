// Reading study files from text in a scratch folder, for the study unit tests.
#pragma once

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "study/study_file.hpp"

namespace rumble::study::testing {

/// A scratch folder with base.json and other.json (their contents do not matter here).
inline std::filesystem::path study_folder() {
  const auto dir = std::filesystem::path(RUMBLE_TEST_BINARY_DIR) / "test_scratch" / "study_unit";
  std::filesystem::create_directories(dir);
  for (const char* name : {"base.json", "other.json"}) std::ofstream(dir / name) << "{}\n";
  return dir;
}

struct ReadResult {
  std::optional<StudyFile> study;
  std::vector<std::string> problems;  // "POINTER: MESSAGE | HINT"
};

inline ReadResult read(const std::string& text) {
  std::vector<scenario::Diagnostic> d;
  ReadResult r;
  auto doc = scenario::parse_document(study_folder() / "study.json", text, d);
  if (doc) r.study = read_study(*doc, d);
  for (const auto& x : d) r.problems.push_back(x.pointer + ": " + x.message + " | " + x.hint);
  return r;
}

}  // namespace rumble::study::testing
