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
#include <string_view>
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

/// This process's environment less what an MPI launcher set (OMPI_*, PMI_*, PMIX_*): a run of a
/// study under mpirun is a process of its own, not one more rank of the launch (which would make
/// it start MPI as a rank it is not). Made before fork: the child only calls execve.
std::vector<std::string> environment_without_launcher() {
  std::vector<std::string> kept;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string_view v(*e);
    if (v.rfind("OMPI_", 0) == 0 || v.rfind("PMI_", 0) == 0 || v.rfind("PMIX_", 0) == 0) continue;
    kept.emplace_back(v);
  }
  return kept;
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
  std::vector<std::string> environment = environment_without_launcher();
  std::vector<char*> envp;
  for (std::string& e : environment) envp.push_back(e.data());
  envp.push_back(nullptr);
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
    ::execve(argv[0], argv.data(), envp.data());
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

/// A run's exit code, state and message from how its child ended (`status` from waitpid). A run
/// that ended without saying how (killed outright) is marked "died" in its summary.
void settle_ended_run(RunRecord& r, int status) {
  if (WIFEXITED(status)) {
    r.exit_code = WEXITSTATUS(status);
  } else {
    r.exit_code = 128 + WTERMSIG(status);
  }
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
}

/// The study's pending runs, started `jobs` at a time, each on its share of the CPUs, and
/// reaped as they end; Ctrl-C starts no more and stops those running.
class PendingRuns {
 public:
  PendingRuns(std::vector<RunRecord>& records, const RunnerOptions& options,
              const std::function<void()>& on_change)
      : records_(records), options_(options), on_change_(on_change) {
    for (std::size_t i = 0; i < records.size(); ++i)
      if (records[i].state == RunState::kPending) queue_.push_back(i);
    total_ = queue_.size();
  }

  /// Runs them all; false when the study was interrupted.
  bool run() {
    while (next_ < queue_.size() || !running_.empty()) {
      if (!stopping_ && interrupt_requested()) stop();
      start_runs();
      int status = 0;
      const pid_t pid = ::waitpid(-1, &status, WNOHANG);
      if (pid < 0 && errno == EINTR) continue;
      const auto it = pid > 0 ? running_.find(pid) : running_.end();
      if (it == running_.end()) {
        std::this_thread::sleep_for(std::chrono::duration<double>(options_.poll_seconds));
        continue;
      }
      ended(it, status);
    }
    return !stopping_;
  }

 private:
  void say(const std::string& line) const {
    if (options_.progress != nullptr) *options_.progress << "study: " << line << std::endl;
  }

  std::size_t jobs() const { return static_cast<std::size_t>(std::max(1, options_.jobs)); }

  /// Ctrl-C: the running runs are told to stop, the others marked as never started.
  void stop() {
    stopping_ = true;
    say("interrupted: starting no more runs; stopping " + std::to_string(running_.size()) +
        " running (Ctrl-C again ends rumble at once)");
    for (const auto& [pid, child] : running_) ::kill(pid, SIGINT);
    for (; next_ < queue_.size(); ++next_) {
      records_[queue_[next_]].state = RunState::kInterrupted;
      records_[queue_[next_]].message = "not started: the study was interrupted";
    }
    on_change_();
  }

  /// As many runs as there are free jobs.
  void start_runs() {
    while (!stopping_ && next_ < queue_.size() && running_.size() < jobs()) {
      RunRecord& r = records_[queue_[next_]];
      std::error_code ec;
      fs::create_directories(r.results, ec);
      if (ec) {
        throw RunError("cannot create the results directory " + r.results.string() + ": " +
                       ec.message() + "; check that the study's output folder is writable");
      }
      const auto free_share = std::find(share_busy_.begin(), share_busy_.end(), false);
      const int share = static_cast<int>(free_share - share_busy_.begin());
      const pid_t pid = start_child(options_.executable, r.command,
                                    cpu_share(cpus_, share, shares_), r.results / "run.log");
      *free_share = true;
      running_[pid] = {queue_[next_], Clock::now(), share};
      r.state = RunState::kRunning;
      ++next_;
      say("started " + r.run.name + " (" + std::to_string(next_) + " of " + std::to_string(total_) +
          ")");
      on_change_();
    }
  }

  /// The child `it` ended with `status`: its record settled, its share freed, the progress said.
  void ended(std::map<pid_t, Child>::iterator it, int status) {
    RunRecord& r = records_[it->second.record];
    share_busy_[static_cast<std::size_t>(it->second.share)] = false;
    const double wall = std::chrono::duration<double>(Clock::now() - it->second.started).count();
    running_.erase(it);
    r.wall_time_s = wall;
    ++done_;
    settle_ended_run(r, status);
    if (r.state != RunState::kInterrupted) {
      finished_wall_ += wall;
      ++finished_;
    }
    say(ended_line(r, wall));
    on_change_();
  }

  /// "completed NAME in 3.2 s; 2 of 5 done, ETA 10 s" (a failure with its exit code, message
  /// and log).
  std::string ended_line(const RunRecord& r, double wall) const {
    std::string line = (r.state == RunState::kCompleted ? "completed " : "") +
                       std::string(r.state == RunState::kFailed ? "FAILED " : "") +
                       (r.state == RunState::kInterrupted ? "interrupted " : "") + r.run.name +
                       " in " + duration_text(wall);
    if (r.state == RunState::kFailed) {
      line += " (exit code " + std::to_string(*r.exit_code) + "): " + r.message + "; log " +
              (r.results / "run.log").lexically_normal().string();
    }
    line += "; " + std::to_string(done_) + " of " + std::to_string(total_) + " done";
    const std::size_t left = (stopping_ ? 0 : queue_.size() - next_) + running_.size();
    if (left > 0 && finished_ > 0 && !stopping_) {
      const double slots = static_cast<double>(std::min<std::size_t>(left, jobs()));
      const double eta =
          finished_wall_ / static_cast<double>(finished_) * static_cast<double>(left) / slots;
      line += ", ETA " + duration_text(eta);
    }
    return line;
  }

  std::vector<RunRecord>& records_;
  const RunnerOptions& options_;
  const std::function<void()>& on_change_;
  std::vector<std::size_t> queue_;  // indices of the pending records, in order
  std::size_t total_ = 0, next_ = 0, done_ = 0;
  double finished_wall_ = 0.0;  // s, sum over runs that ended by themselves
  std::size_t finished_ = 0;
  std::map<pid_t, Child> running_;
  const int shares_ = std::max(1, options_.jobs);
  const std::vector<int> cpus_ = usable_cpu_list();
  std::vector<bool> share_busy_ = std::vector<bool>(static_cast<std::size_t>(shares_), false);
  bool stopping_ = false;
};

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
  PendingRuns pending(records, options, on_change);
  return pending.run();
}

}  // namespace rumble::study
