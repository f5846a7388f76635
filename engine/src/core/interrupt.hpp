// Ctrl-C: the first SIGINT/SIGTERM sets a flag that the run loop checks after every macro step,
// so the run stops cleanly with its results on disk; a second one ends the process at once.
#pragma once

namespace rumble {

void install_interrupt_handler();
bool interrupt_requested();
void request_interrupt();  // what the handler does; also for tests
void clear_interrupt();
/// What asked to stop, for messages: "SIGTERM" (a kill, a job scheduler's time limit) or "Ctrl-C"
/// (SIGINT, or a request in code).
const char* interrupt_cause();

}  // namespace rumble
