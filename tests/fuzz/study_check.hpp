// What the study fuzz target checks for one input (a study file's text), shared by the libFuzzer
// target (fuzz_target.cpp, preset "fuzz") and the replay test of the other presets
// (replay_test.cpp).
#pragma once

#include <string>
#include <string_view>

namespace rumble::fuzz {

/// Puts `text` through what `rumble study FILE --dry-run` does before any run starts, as
/// the study file study.json of a scratch folder holding the scenarios base.json, other.json
/// and scenario.json (tests/scenario/valid/minimal.json) and track_on_fem_soil.json (the paper
/// study's): parse, read_study, expand, the output folder's place, and for the first runs and
/// the last what prepare_runs checks, with --no-load (no plugin library is loaded): the run's
/// scenario read with its patches applied and checked, and the run key of a valid one.
/// Returns "" when every property holds, else what broke:
///   - nothing escapes as an exception but the ConfigError of a patch that cannot be applied,
///     whose message names the study file and the patch's place in it;
///   - a study that is refused says why: a diagnostic with a message and a line inside the
///     text (or none), both reports print; a study that is read has no diagnostic;
///   - the runs are bounded: at most kMaxStudyRuns, the axes' product and the listed runs (or
///     none, with a diagnostic, when two share a name); each name can name a directory;
///   - nothing is written: the scratch folder is unchanged and the output folder not made;
///   - the runs checked get distinct keys.
std::string check_study_text(std::string_view text);

}  // namespace rumble::fuzz
