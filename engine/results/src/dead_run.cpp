#include "results/dead_run.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "core/input_file.hpp"
#include "results/new_file.hpp"
#include "results/results_directory.hpp"
#include "results/run_status.hpp"

namespace rumble {

namespace fs = std::filesystem;

namespace {

std::string died_message(const nlohmann::json& summary) {
  std::ostringstream m;
  m << "the run died without a word (a kill -9, a crash it could not record, or the machine "
       "stopping): ";
  const nlohmann::json& beat = summary.value("heartbeat", nlohmann::json::object());
  if (beat.contains("t_s") && beat["t_s"].is_number()) {
    m << "it had reached t = " << beat["t_s"].get<double>() << " s ("
      << beat.value("macro_steps", 0) << " macro steps) at its last heartbeat, "
      << beat.value("utc", std::string("?")) << "; ";
  }
  if (const auto p = summary.find("process"); p != summary.end() && p->is_object())
    m << "process " << p->value("pid", 0) << " on " << p->value("host", std::string("?")) << "; ";
  m << "the results up to about that time are on disk";
  return m.str();
}

}  // namespace

std::string settle_dead_run(const fs::path& dir) noexcept {
  try {
    const fs::path file = dir / "summary.json";
    if (!input_file_problem(file, kMaxResultJsonBytes).empty()) return "";
    nlohmann::json summary = nlohmann::json::parse(read_input_file(file, kMaxResultJsonBytes));
    if (!summary.is_object() || summary.value("status", "") != status_name(RunStatus::kRunning))
      return "";
    const std::string message = died_message(summary);
    summary["status"] = "died";
    summary["message"] = message;
    replace_file(file, dir / "summary.json.tmp", summary.dump(2) + '\n');
    return message;
  } catch (const std::exception&) {
    return "";  // a summary that cannot be read or rewritten stays as it is
  }
}

std::string settle_dead_run_if_unlocked(const fs::path& dir) noexcept {
  const fs::path lock = dir / ResultsDirectory::kLockFile;
  const int fd = ::open(lock.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return "";
  std::string message;
  if (::flock(fd, LOCK_EX | LOCK_NB) == 0) message = settle_dead_run(dir);
  ::close(fd);  // the lock goes with it
  return message;
}

}  // namespace rumble
