// Ctrl-C: the first SIGINT/SIGTERM sets a flag that the run loop checks after every macro step,
// so the run stops cleanly with its results on disk; a second one ends the process at once.
//
// Some phases cannot look at the flag between their own pieces (a dense LU of the statics,
// gmsh's meshing, a sparse factorisation inside a plugin). Every phase must still stop within a
// second or two (issue #30), so a signal also starts a deadline: when the process has not ended
// `grace` seconds after the first signal, a watchdog thread says which phase held it (stderr,
// and the command's last word: a run marks summary.json "interrupted"), then ends the process
// with std::_Exit. docs/scenario.md, "Stopping a run".
#pragma once

#include <functional>

namespace rumble {

/// Seconds a phase has to honour a stop request before the process is ended for it.
inline constexpr double kStopGraceSeconds = 1.5;

/// Installs the SIGINT/SIGTERM handler and the deadline's watchdog (once per process; a later
/// call only changes the grace): `grace_s` after the first signal the process ends with exit
/// code 130 unless a last word says otherwise. A study gives its runs their own grace first.
void install_interrupt_handler(double grace_s = kStopGraceSeconds);
bool interrupt_requested();
void request_interrupt();  // what the handler does (without the deadline); also for tests
void clear_interrupt();
/// What asked to stop, for messages: "SIGTERM" (a kill, a job scheduler's time limit) or "Ctrl-C"
/// (SIGINT, or a request in code).
const char* interrupt_cause();

/// What the watchdog calls before ending the process at the deadline, with the phase that held
/// it; returns the exit code. Called on the watchdog's thread while the phase still runs on its
/// own, so it may only touch what it guards itself.
using LastWord = std::function<int(const char* phase)>;

/// While it lives, the deadline's last word is `word` (a run's: summary.json "interrupted").
class LastWordScope {
 public:
  explicit LastWordScope(LastWord word);
  ~LastWordScope();
  LastWordScope(const LastWordScope&) = delete;
  LastWordScope& operator=(const LastWordScope&) = delete;
};

/// While it lives, the phase the deadline names is `phase`: a string that outlives it ("the
/// static state"). Phases nest; the innermost is named.
class StopPhase {
 public:
  explicit StopPhase(const char* phase) noexcept;
  ~StopPhase();
  StopPhase(const StopPhase&) = delete;
  StopPhase& operator=(const StopPhase&) = delete;

 private:
  const char* previous_;
};

}  // namespace rumble
