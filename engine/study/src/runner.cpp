#include "study/runner.hpp"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <ostream>
#include <thread>

#include "core/cpu_affinity.hpp"
#include "core/errors.hpp"
#include "core/input_file.hpp"
#include "core/interrupt.hpp"
#include "results/dead_run.hpp"
#include "results/new_file.hpp"

namespace rumble::study {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Child {
  std::size_t record = 0;
  Clock::time_point started;
  int share = 0;  // which of the study's CPU shares it runs on
};

/// The last "error:" line of a run's log (what the child said when it failed), or "".
std::string last_error(const fs::path& log) {
  if (!input_file_problem(log, kMaxResultJsonBytes).empty()) return "";
  std::ifstream in(log);
  std::string line, found;
  while (std::getline(in, line)) {
    if (line.find("error:") != std::string::npos) found = line;
  }
  if (const auto at = found.find("rumble: error: "); at == 0) found = found.substr(15);
  if (found.size() > 300) found = found.substr(0, 300) + "...";
  return found;
}

std::string summary_status(const fs::path& dir) {
  try {
    const auto j =
        nlohmann::json::parse(read_input_file(dir / "summary.json", kMaxResultJsonBytes));
    return j.value("status", "");
  } catch (const std::exception&) {
    return "";
  }
}

/// Starts one child: its own process group (the terminal's Ctrl-C reaches the study only, which
/// forwards it once), on `cpus` (its share of the study's: a run gives its soil as many threads
/// as it may use CPUs, so runs side by side must not each see all of them), stdin from
/// /dev/null, stdout and stderr into `log`.
pid_t start_child(const fs::path& executable, const std::vector<std::string>& command,
                  const std::vector<int>& cpus, const fs::path& log) {
  const int log_fd = open_new_file(log);
  std::vector<std::string> args;
  args.push_back(executable.string());
  args.insert(args.end(), command.begin(), command.end());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t study = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::setpgid(0, 0);
    // The run dies with the study, even one killed outright (SIGKILL, a crash): the kernel then
    // sends it SIGTERM, which stops a run cleanly with what it finished on disk. (The study
    // forks from its main thread, whose exit is what the kernel watches.) A study that died
    // before this line is seen as a new parent.
    if (::prctl(PR_SET_PDEATHSIG, SIGTERM) != 0 || ::getppid() != study) ::_exit(128 + SIGTERM);
    restrict_to_cpus(cpus);  // where refused, the run shares all of them: slower, still right
    const int null = ::open("/dev/null", O_RDONLY);
    if (null >= 0) ::dup2(null, STDIN_FILENO);
    ::dup2(log_fd, STDOUT_FILENO);
    ::dup2(log_fd, STDERR_FILENO);
    ::signal(SIGINT, SIG_DFL);
    ::signal(SIGTERM, SIG_DFL);
    ::execv(argv[0], argv.data());
    const char* why = std::strerror(errno);
    const char prefix[] = "rumble: error: cannot start the run: ";
    if (::write(STDERR_FILENO, prefix, sizeof prefix - 1) < 0 ||
        ::write(STDERR_FILENO, why, std::strlen(why)) < 0 || ::write(STDERR_FILENO, "\n", 1) < 0) {
      // Nothing more to say it with.
    }
    ::_exit(127);
  }
  const int err = errno;
  ::close(log_fd);
  if (pid < 0)
    throw RunError(std::string("cannot start a run: fork failed: ") + std::strerror(err));
  return pid;
}

}  // namespace

std::string duration_text(double s) {
  char text[48];
  if (s < 10.0) {
    std::snprintf(text, sizeof text, "%.1f s", s);
  } else if (s < 60.0) {
    std::snprintf(text, sizeof text, "%.0f s", s);
  } else if (s < 3600.0) {
    const long t = static_cast<long>(s + 0.5);
    std::snprintf(text, sizeof text, "%ld min %02ld s", t / 60, t % 60);
  } else {
    const long m = static_cast<long>(s / 60.0 + 0.5);
    std::snprintf(text, sizeof text, "%ld h %02ld min", m / 60, m % 60);
  }
  return text;
}

bool run_pending(std::vector<RunRecord>& records, const RunnerOptions& options,
                 const std::function<void()>& on_change) {
  std::vector<std::size_t> queue;
  for (std::size_t i = 0; i < records.size(); ++i)
    if (records[i].state == RunState::kPending) queue.push_back(i);
  const std::size_t total = queue.size();
  std::size_t next = 0, done = 0;
  double finished_wall = 0.0;  // s, sum over runs that ended by themselves
  std::size_t finished = 0;
  std::map<pid_t, Child> running;
  const int shares = std::max(1, options.jobs);
  const std::vector<int> cpus = usable_cpu_list();
  std::vector<bool> share_busy(static_cast<std::size_t>(shares), false);
  bool stopping = false;
  const auto say = [&](const std::string& line) {
    if (options.progress != nullptr) *options.progress << "study: " << line << std::endl;
  };

  while (next < queue.size() || !running.empty()) {
    if (!stopping && interrupt_requested()) {
      stopping = true;
      say("interrupted: starting no more runs; stopping " + std::to_string(running.size()) +
          " running (Ctrl-C again ends rumble at once)");
      for (const auto& [pid, child] : running) ::kill(pid, SIGINT);
      for (; next < queue.size(); ++next) {
        records[queue[next]].state = RunState::kInterrupted;
        records[queue[next]].message = "not started: the study was interrupted";
      }
      on_change();
    }
    while (!stopping && next < queue.size() &&
           running.size() < static_cast<std::size_t>(std::max(1, options.jobs))) {
      RunRecord& r = records[queue[next]];
      std::error_code ec;
      fs::create_directories(r.results, ec);
      if (ec) {
        throw RunError("cannot create the results directory " + r.results.string() + ": " +
                       ec.message() + "; check that the study's output folder is writable");
      }
      const auto free_share = std::find(share_busy.begin(), share_busy.end(), false);
      const int share = static_cast<int>(free_share - share_busy.begin());
      const pid_t pid = start_child(options.executable, r.command, cpu_share(cpus, share, shares),
                                    r.results / "run.log");
      *free_share = true;
      running[pid] = {queue[next], Clock::now(), share};
      r.state = RunState::kRunning;
      ++next;
      say("started " + r.run.name + " (" + std::to_string(next) + " of " + std::to_string(total) +
          ")");
      on_change();
    }
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, WNOHANG);
    if (pid < 0 && errno == EINTR) continue;
    const auto it = pid > 0 ? running.find(pid) : running.end();
    if (it == running.end()) {
      std::this_thread::sleep_for(std::chrono::duration<double>(options.poll_seconds));
      continue;
    }
    RunRecord& r = records[it->second.record];
    share_busy[static_cast<std::size_t>(it->second.share)] = false;
    const double wall = std::chrono::duration<double>(Clock::now() - it->second.started).count();
    running.erase(it);
    r.wall_time_s = wall;
    ++done;
    if (WIFEXITED(status)) {
      r.exit_code = WEXITSTATUS(status);
    } else {
      r.exit_code = 128 + WTERMSIG(status);
    }
    // A run that ended without saying how (killed outright) is marked "died" in its summary.
    if (WIFSIGNALED(status)) settle_dead_run_if_unlocked(r.results);
    const std::string summary = summary_status(r.results);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
      r.state = RunState::kCompleted;
      r.message.clear();
    } else if (summary == "interrupted") {
      r.state = RunState::kInterrupted;
      r.message = "interrupted";
    } else {
      r.state = RunState::kFailed;
      r.message = WIFSIGNALED(status)
                      ? std::string("ended by signal ") + std::to_string(WTERMSIG(status)) + " (" +
                            strsignal(WTERMSIG(status)) + ")"
                      : last_error(r.results / "run.log");
      if (r.message.empty()) r.message = "exit code " + std::to_string(*r.exit_code);
    }
    if (r.state != RunState::kInterrupted) {
      finished_wall += wall;
      ++finished;
    }
    std::string line = (r.state == RunState::kCompleted ? "completed " : "") +
                       std::string(r.state == RunState::kFailed ? "FAILED " : "") +
                       (r.state == RunState::kInterrupted ? "interrupted " : "") + r.run.name +
                       " in " + duration_text(wall);
    if (r.state == RunState::kFailed) {
      line += " (exit code " + std::to_string(*r.exit_code) + "): " + r.message + "; log " +
              (r.results / "run.log").lexically_normal().string();
    }
    line += "; " + std::to_string(done) + " of " + std::to_string(total) + " done";
    const std::size_t left = (stopping ? 0 : queue.size() - next) + running.size();
    if (left > 0 && finished > 0 && !stopping) {
      const double slots = static_cast<double>(
          std::min<std::size_t>(left, static_cast<std::size_t>(std::max(1, options.jobs))));
      const double eta =
          finished_wall / static_cast<double>(finished) * static_cast<double>(left) / slots;
      line += ", ETA " + duration_text(eta);
    }
    say(line);
    on_change();
  }
  return !stopping;
}

}  // namespace rumble::study
