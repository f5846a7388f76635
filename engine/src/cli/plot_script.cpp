#include "cli/plot_script.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <boost/dll/runtime_symbol_info.hpp>

#include "core/logging.hpp"

namespace rumble::cli {
namespace {

namespace fs = std::filesystem;

fs::path find_script(const std::string& script) {
  // Installed next to the executable (share/rumble), or the source tree's tools/.
  const fs::path exe_dir = boost::dll::program_location().parent_path();
  for (const fs::path& candidate : {exe_dir.parent_path() / "share" / "rumble" / script,
                                    fs::path(RUMBLE_SOURCE_DIR) / "tools" / script}) {
    if (fs::exists(candidate)) return candidate;
  }
  return {};
}

}  // namespace

bool run_plot_script(const std::string& script, const fs::path& directory) {
  const auto log = logger("engine");
  const fs::path path = find_script(script);
  const char* python = "/usr/bin/python3";
  if (path.empty() || access(python, X_OK) != 0) {
    log->warn("plots skipped: {} or {} not found (install python3-matplotlib)", script, python);
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
