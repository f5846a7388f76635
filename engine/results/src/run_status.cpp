#include "results/run_status.hpp"

namespace rumble {

const char* status_name(RunStatus status) {
  switch (status) {
    case RunStatus::kRunning:
      return "running";
    case RunStatus::kCompleted:
      return "completed";
    case RunStatus::kInterrupted:
      return "interrupted";
    case RunStatus::kFailed:
      return "failed";
    case RunStatus::kAborted:
      return "aborted";
  }
  return "failed";
}

int exit_code(RunStatus status) {
  return status == RunStatus::kCompleted ? 0 : 3;
}

}  // namespace rumble
