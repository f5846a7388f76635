// How a run ended, as summary.json spells it and as the process exit code says it
// (docs/scenario.md, "summary.json"). Here rather than with the summary writer so that whoever
// reads a results directory (a study, `rumble post`, a rerun settling a dead run) needs no run.
#pragma once

namespace rumble {

enum class RunStatus { kRunning, kCompleted, kInterrupted, kFailed, kAborted };

/// "running", "completed", "interrupted", "failed", "aborted" (as summary.json spells them).
const char* status_name(RunStatus status);
/// The process exit code of a run that ended so: 0 completed, 3 otherwise (exit_codes.hpp).
int exit_code(RunStatus status);

}  // namespace rumble
