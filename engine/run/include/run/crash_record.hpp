// A run that crashes (a plugin's SIGSEGV, SIGBUS, SIGFPE or SIGILL, or an abort()) says so in
// summary.json before the process ends: status "crashed", the signal, and the participant that
// was stepping on the thread that crashed ("the engine" outside a step), beside the last
// heartbeat. The handler writes text SummaryWriter keeps rendered (SummaryWriter::crashed), so it
// allocates nothing and takes no lock; then the signal takes its default course (a core dump
// where enabled, exit status 128 + signal). A crash inside the handler or a SIGKILL leaves
// "running", which the next look at the directory reports as "died" (results/dead_run.hpp).
// docs/scenario.md, "summary.json".
#pragma once

namespace rumble {

class SummaryWriter;

/// Installs the handlers for one run (on an alternate stack, so that a stack overflow is
/// recorded too) and removes them when it ends.
class CrashRecord {
 public:
  explicit CrashRecord(SummaryWriter& summary);
  ~CrashRecord();
  CrashRecord(const CrashRecord&) = delete;
  CrashRecord& operator=(const CrashRecord&) = delete;
};

/// While it lives, a crash on this thread is charged to `participant` ("soil/fem"): a string
/// that outlives it.
class SteppingParticipant {
 public:
  explicit SteppingParticipant(const char* participant) noexcept;
  ~SteppingParticipant();
  SteppingParticipant(const SteppingParticipant&) = delete;
  SteppingParticipant& operator=(const SteppingParticipant&) = delete;

 private:
  const char* previous_;
};

}  // namespace rumble
