#include "run/summary_writer.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string_view>

#include "core/cpu_affinity.hpp"
#include "core/errors.hpp"
#include "plugin/registry.hpp"
#include "results/new_file.hpp"
#include "results/results_directory.hpp"
#include "run/run_components.hpp"

namespace rumble {

namespace fs = std::filesystem;

namespace {

// Stands for the heartbeat's value in the dumped summary; only a top-level key sits at the start
// of a line indented by two, so this text occurs once.
constexpr std::string_view kHeartbeatKey = "\n  \"heartbeat\": ";
constexpr const char* kPlaceholder = "@heartbeat@";

}  // namespace

SummaryWriter::SummaryWriter(ResultsDirectory& results, const scenario::RunSpec& spec,
                             const RunComponents& components, double heartbeat_seconds)
    : path_(results.file("summary.json")),
      tmp_(results.file("summary.json.tmp")),
      heartbeat_interval_(std::chrono::duration_cast<Clock::duration>(
          std::chrono::duration<double>(heartbeat_seconds))) {
  summary_["rumble_version"] = RUMBLE_VERSION;
  summary_["scenario_file"] = fs::absolute(spec.path).string();
  summary_["scenario"] = spec.document;
  summary_["overrides"] = spec.overrides;
  summary_["status"] = status_name(RunStatus::kRunning);
  char host[256] = {};
  if (::gethostname(host, sizeof host - 1) != 0) host[0] = '\0';
  summary_["process"] = {{"pid", ::getpid()}, {"host", host}, {"cpus", usable_cpu_list()}};
  nlohmann::json plugins = nlohmann::json::array();
  for (const Instance* inst : components.instances()) {
    const PluginIdentity& id = inst->type().library->identity;
    plugins.push_back({{"type", inst->type_name()},
                       {"kind", kind_name(inst->type().kind)},
                       {"at", inst->label()},
                       {"plugin", id.name},
                       {"version", id.version},
                       {"abi", id.abi()},
                       {"path", inst->type().library->path.string()}});
  }
  summary_["plugins"] = plugins;
  write();
}

void SummaryWriter::heartbeat(double t, std::size_t steps) {
  const std::lock_guard lock(mutex_);
  if (sealed_) return;
  t_ = t;
  steps_ = steps;
  if (Clock::now() < next_heartbeat_) return;
  if (changed_) {
    write();
    return;
  }
  char beat[192];
  write_pieces(beat, format_heartbeat(beat, sizeof beat));
}

void SummaryWriter::finish(RunStatus status, const std::string& message) {
  const std::lock_guard lock(mutex_);
  if (sealed_) return;
  summary_["status"] = status_name(status);
  if (!message.empty()) summary_["message"] = message;
  write();
}

void SummaryWriter::fail(const std::string& message, RunStatus status) noexcept {
  try {
    const std::lock_guard lock(mutex_);
    if (sealed_) return;
    summary_["status"] = status_name(status);
    summary_["message"] = message;
    write();
  } catch (...) {
    // The disk refused the summary too; the caller reports the original error.
  }
}

void SummaryWriter::stopped_at_deadline(const std::string& message) noexcept {
  try {
    const std::lock_guard lock(mutex_);
    if (sealed_) return;
    summary_["status"] = status_name(RunStatus::kInterrupted);
    summary_["message"] = message;
    write();
    sealed_ = true;
  } catch (...) {
    // The disk refused it: the next look at the directory finds the run dead
    // (results/dead_run.hpp).
  }
}

std::size_t SummaryWriter::format_heartbeat(char* buffer, std::size_t size) const {
  // Calendar arithmetic, not gmtime: the first call of that loads time zone data (allocating).
  using namespace std::chrono;
  const auto now = system_clock::now();
  const auto day = floor<days>(now);
  const year_month_day date{day};
  const hh_mm_ss time{floor<seconds>(now - day)};
  char t[32] = "null";  // JSON has no nan
  if (std::isfinite(t_)) std::snprintf(t, sizeof t, "%.9g", t_);
  const int n = std::snprintf(
      buffer, size,
      R"({"t_s": %s, "macro_steps": %zu, "utc": "%04d-%02u-%02uT%02d:%02d:%02dZ", )"
      R"("unix_time_s": %.3f})",
      t, steps_, static_cast<int>(date.year()), static_cast<unsigned>(date.month()),
      static_cast<unsigned>(date.day()), static_cast<int>(time.hours().count()),
      static_cast<int>(time.minutes().count()), static_cast<int>(time.seconds().count()),
      duration<double>(now.time_since_epoch()).count());
  return n < 0 ? 0 : std::min(static_cast<std::size_t>(n), size - 1);
}

void SummaryWriter::write() {
  summary_["heartbeat"] = kPlaceholder;
  const std::string text = summary_.dump(2) + '\n';
  const std::string placeholder = std::string(kHeartbeatKey) + '"' + kPlaceholder + '"';
  const std::size_t at = text.find(placeholder);
  if (at == std::string::npos)
    throw std::logic_error("summary.json: the heartbeat's place is lost");
  prefix_ = text.substr(0, at + kHeartbeatKey.size());
  suffix_ = text.substr(at + placeholder.size());
  crashed_suffix_ = suffix_;
  const std::string running = std::string("\n  \"status\": \"") + status_name(RunStatus::kRunning);
  constexpr std::string_view kCrashed = "crashed";  // as long as "running": same offsets
  if (const std::size_t s = crashed_suffix_.find(running + '"'); s != std::string::npos)
    crashed_suffix_.replace(s + running.size() - kCrashed.size(), kCrashed.size(), kCrashed);
  changed_ = false;
  char beat[192];
  write_pieces(beat, format_heartbeat(beat, sizeof beat));
}

void SummaryWriter::crashed(int sig, const char* participant) noexcept {
  // `, "crash": {...}` follows the heartbeat's value: valid JSON whether the summary goes on
  // with another key (",") or closes ("}"). Built by hand: no allocation, no locale.
  char crash[256];
  std::size_t n = 0;
  const auto add = [&](const char* text) {  // room is kept for the closing "}
    for (; *text != '\0' && n + 8 < sizeof crash; ++text)
      if (*text != '"' && *text != '\\' && static_cast<unsigned char>(*text) >= 0x20)
        crash[n++] = *text;
  };
  const auto add_raw = [&](std::string_view text) {
    for (const char c : text)
      if (n + 1 < sizeof crash) crash[n++] = c;
  };
  add_raw(",\n  \"crash\": {\"signal\": \"SIG");
  const char* name = ::sigabbrev_np(sig);
  add(name != nullptr ? name : "?");
  add_raw("\", \"participant\": \"");
  add(participant);
  add_raw("\"}");
  (void)replace_file_noexcept(path_.c_str(), tmp_.c_str(),
                              {prefix_, std::string_view(beat_.data(), beat_length_),
                               std::string_view(crash, n), crashed_suffix_});
}

void SummaryWriter::write_pieces(const char* heartbeat, std::size_t length) {
  beat_length_ = std::min(length, beat_.size());
  std::copy_n(heartbeat, beat_length_, beat_.data());
  const int err = replace_file_noexcept(path_.c_str(), tmp_.c_str(),
                                        {prefix_, std::string_view(heartbeat, length), suffix_});
  if (err != 0) throw RunError(write_error(path_, err));
  next_heartbeat_ = Clock::now() + heartbeat_interval_;
}

}  // namespace rumble
