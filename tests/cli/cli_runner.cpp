#include "cli_runner.hpp"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <csignal>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace rumble::testing {

CliResult run_rumble(const std::vector<std::string>& args, const RunSetup& setup) {
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("pipe failed");
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(fds[1], STDOUT_FILENO);
    dup2(fds[1], STDERR_FILENO);
    close(fds[0]);
    close(fds[1]);
    if (!setup.stdin_file.empty()) {
      const int in = open(setup.stdin_file.c_str(), O_RDONLY);
      dup2(in, STDIN_FILENO);
      close(in);
    }
    if (setup.file_size_limit >= 0) {
      const rlimit limit{static_cast<rlim_t>(setup.file_size_limit),
                         static_cast<rlim_t>(setup.file_size_limit)};
      setrlimit(RLIMIT_FSIZE, &limit);
      std::signal(SIGXFSZ, SIG_IGN);  // stays ignored across exec
    }
    for (const auto& [name, value] : setup.environment) setenv(name.c_str(), value.c_str(), 1);
    std::vector<char*> argv;
    std::string exe = RUMBLE_TEST_EXE;
    argv.push_back(exe.data());
    std::vector<std::string> copy = args;
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(exe.c_str(), argv.data());
    _exit(127);
  }
  close(fds[1]);
  CliResult result;
  std::array<char, 4096> buffer;
  ssize_t n;
  while ((n = read(fds[0], buffer.data(), buffer.size())) > 0)
    result.output.append(buffer.data(), static_cast<std::size_t>(n));
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

pid_t start_rumble(const std::vector<std::string>& args, const std::filesystem::path& output) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int sink = output.empty() ? open("/dev/null", O_WRONLY)
                                    : open(output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(sink, STDOUT_FILENO);
    dup2(sink, STDERR_FILENO);
    std::string exe = RUMBLE_TEST_EXE;
    std::vector<std::string> copy = args;
    std::vector<char*> argv{exe.data()};
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(exe.c_str(), argv.data());
    _exit(127);
  }
  return pid;
}

int wait_rumble(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::filesystem::path scratch_directory(const std::string& test_name) {
  const auto dir = std::filesystem::path(RUMBLE_TEST_BINARY_DIR) / "test_scratch" / test_name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

nlohmann::json small_scenario() {
  return {{"schema_version", 1},
          {"name", "cli test: single wheel on winkler"},
          {"time", {{"end", 0.05}, {"macro_step", 1e-3}}},
          {"vehicles",
           {{{"type", "single_wheel"},
             {"speed", 20.0},
             {"start", 3.0},
             {"params", {{"mass", 750.0}, {"static_load", 50000.0}}}}}},
          {"track",
           {{"sleepers",
             {{"count", 20},
              {"spacing", 0.6},
              {"mass", 150.0},
              {"footprint", {{"length", 2.6}, {"width", 0.26}}}}},
            {"rail", {{"E", 2.1e11}, {"I", 3.055e-5}, {"mass_per_length", 60.34}}},
            {"railpad", {{"k", 2e8}, {"c", 2.8e4}}},
            {"ballast", {{"k", 4e7}, {"c", 4.7e4}}}}},
          {"soil", {{"type", "winkler"}, {"params", {{"k", 1e8}, {"c", 2e5}}}}},
          {"coupling", {{"type", "gauss_seidel"}, {"params", nlohmann::json::object()}}},
          {"outputs", {{"directory", "results"}, {"plots", false}}}};
}

nlohmann::json small_fem_scenario() {
  nlohmann::json s = small_scenario();
  s["track"]["sleepers"]["count"] = 10;
  s["soil"] = {{"type", "fem"},
               {"params",
                {{"E", 750e6},
                 {"nu", 0.3},
                 {"rho", 1800.0},
                 {"mesh", {{"radius", 6.0}, {"f_max", 40.0}, {"near_distance", 1.5}}}}}};
  return s;
}

std::filesystem::path write_scenario(const std::filesystem::path& dir, const nlohmann::json& s) {
  const auto path = dir / "scenario.json";
  std::ofstream(path) << s.dump(2) << '\n';
  return path;
}

std::size_t csv_rows(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  std::size_t rows = 0;
  while (std::getline(in, line)) ++rows;
  return rows == 0 ? 0 : rows - 1;
}

nlohmann::json read_json(const std::filesystem::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

void read_csv(const std::filesystem::path& file, std::vector<double>& times,
              std::vector<double>& values) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream row(line);
    double x = 0.0;
    row >> x;
    times.push_back(x);
    while (row >> x) values.push_back(x);
  }
}

std::string file_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace rumble::testing
