// Before anything runs: every run's scenario is read with its patches applied and checked as
// `rumble validate` would; a valid run gets its key and the command line of its child process,
// an invalid one is reported (all of them at once) and will not run. docs/study.md.
#pragma once

#include <iosfwd>
#include <vector>

#include "study/expansion.hpp"
#include "study/study_file.hpp"
#include "study/study_state.hpp"

namespace rumble {
class PluginRegistry;
}

namespace rumble::study {

/// One record per planned run, in order: kPending with key and command, or kInvalid with the
/// reason in its message (the findings printed to `report`). The registry holds the default
/// plugin directories; the plugins scenarios list are loaded into it. size_confirmed (`study
/// --yes`): runs beyond the size limits (scenario/run_size.hpp) are wanted, and run with --yes.
std::vector<RunRecord> prepare_runs(const StudyFile& study, std::vector<PlannedRun> runs,
                                    PluginRegistry& registry, std::ostream& report,
                                    bool size_confirmed = false);

}  // namespace rumble::study
