#include "cli/plot_script.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include "cli/share_dir.hpp"
#include "core/logging.hpp"

namespace rumble::cli {

namespace fs = std::filesystem;

bool run_plot_script(const std::string& script, const fs::path& directory) {
  const auto log = logger("engine");
  // Installed with the engine, and copied into the build tree's share/rumble by the build.
  const fs::path path = share_directory() / script;
  if (!fs::exists(path)) {
    log->warn(
        "plots skipped: {} not found (the plot scripts belong in share/rumble next to the bin/ "
        "holding rumble); reinstall Rumble with cmake --install, or rebuild it",
        path.string());
    return false;
  }
  const char* python = "/usr/bin/python3";
  if (access(python, X_OK) != 0) {
    log->warn("plots skipped: {} not found; install python3 and python3-matplotlib", python);
    return false;
  }
  const pid_t pid = fork();
  if (pid == 0) {
    execl(python, python, path.c_str(), directory.c_str(), nullptr);
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    log->warn("plots failed: {} {} exited with status {}; the CSV results are complete",
              path.string(), directory.string(), WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    return false;
  }
  return true;
}

}  // namespace rumble::cli
