#include "study/study_state.hpp"

#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/input_file.hpp"
#include "results/new_file.hpp"

namespace rumble::study {
namespace {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

std::string utc_now() {
  using namespace std::chrono;
  const auto now = system_clock::now();
  const auto day = floor<days>(now);
  const year_month_day date{day};
  const hh_mm_ss time{floor<seconds>(now - day)};
  char text[32];
  std::snprintf(text, sizeof text, "%04d-%02u-%02uT%02d:%02d:%02dZ", static_cast<int>(date.year()),
                static_cast<unsigned>(date.month()), static_cast<unsigned>(date.day()),
                static_cast<int>(time.hours().count()), static_cast<int>(time.minutes().count()),
                static_cast<int>(time.seconds().count()));
  return text;
}

std::optional<nlohmann::json> read_json(const fs::path& p) {
  if (!input_file_problem(p, kMaxResultJsonBytes).empty()) return std::nullopt;
  try {
    return nlohmann::json::parse(read_input_file(p, kMaxResultJsonBytes));
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

}  // namespace

const char* state_name(RunState state) {
  switch (state) {
    case RunState::kPending:
      return "pending";
    case RunState::kRunning:
      return "running";
    case RunState::kCompleted:
      return "completed";
    case RunState::kInvalid:
    case RunState::kFailed:
      return "failed";
    case RunState::kInterrupted:
      return "interrupted";
    case RunState::kSkipped:
      return "skipped";
  }
  return "failed";
}

std::map<std::string, PreviousRun> read_previous_state(const fs::path& study_json) {
  std::map<std::string, PreviousRun> out;
  const auto j = read_json(study_json);
  if (!j || !j->is_object() || !j->contains("runs") || !(*j)["runs"].is_array()) return out;
  for (const auto& r : (*j)["runs"]) {
    if (!r.is_object() || !r.contains("name") || !r["name"].is_string()) continue;
    PreviousRun p;
    if (r.contains("key") && r["key"].is_string()) p.key = r["key"].get<std::string>();
    if (r.contains("status") && r["status"].is_string()) p.status = r["status"].get<std::string>();
    out[r["name"].get<std::string>()] = p;
  }
  return out;
}

bool up_to_date(const std::map<std::string, PreviousRun>& previous, const RunRecord& record) {
  const auto it = previous.find(record.run.name);
  if (record.key.empty() || it == previous.end() || it->second.key != record.key) return false;
  if (it->second.status != "completed" && it->second.status != "skipped") return false;
  const auto summary = read_json(record.results / "summary.json");
  return summary && summary->is_object() && summary->value("status", "") == "completed";
}

void write_state(const fs::path& study_json, const StudyFile& study,
                 const std::vector<RunRecord>& records, const std::string& status, int jobs) {
  ojson j;
  j["about"] = "the state of every run of a rumble study (docs/study.md)";
  j["study_file"] = fs::absolute(study.path).lexically_normal().string();
  j["name"] = study.name;
  j["description"] = study.description;
  j["rumble_version"] = RUMBLE_VERSION;
  j["status"] = status;
  j["updated_utc"] = utc_now();
  j["jobs"] = jobs;
  j["output"] = fs::absolute(study.output).lexically_normal().string();
  j["axes"] = ojson::array();
  for (const Axis& a : study.axes) {
    ojson values = ojson::array();
    for (const AxisValue& v : a.values) values.push_back(v.name);
    j["axes"].push_back({{"name", a.name}, {"values", values}});
  }
  j["runs"] = ojson::array();
  for (const RunRecord& r : records) {
    ojson e;
    e["name"] = r.run.name;
    e["status"] = state_name(r.state);
    e["scenario_file"] = fs::absolute(r.run.scenario).lexically_normal().string();
    e["axis_values"] = r.run.axis_values;
    e["patches"] = ojson::array();
    for (const Patch& p : r.run.patches)
      e["patches"].push_back({{"pointer", p.pointer}, {"value", ojson::parse(p.value.dump())}});
    e["key"] = r.key.empty() ? ojson() : ojson(r.key);
    e["exit_code"] = r.exit_code ? ojson(*r.exit_code) : ojson();
    e["wall_time_s"] = r.wall_time_s ? ojson(*r.wall_time_s) : ojson();
    e["results"] = fs::absolute(r.results).lexically_normal().string();
    e["log"] = fs::absolute(r.results / "run.log").lexically_normal().string();
    if (!r.message.empty()) e["message"] = r.message;
    if (r.rank) e["mpi"] = {{"rank", *r.rank}, {"host", r.host}};
    j["runs"].push_back(std::move(e));
  }
  replace_file(study_json, fs::path(study_json.string() + ".tmp"),
               j.dump(2, ' ', false, ojson::error_handler_t::replace) + "\n");
}

}  // namespace rumble::study
