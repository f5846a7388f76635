// Reading a run's results for post-processing. What post accepts from a results directory, and
// every message about a bad one, is decided here and nowhere else, so that the measuring can
// trust the record it is given (docs/post-processing.md, "Input: the results directory").
#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "core/input_file.hpp"
#include "core/number_text.hpp"
#include "post_run_steps.hpp"

namespace rumble::post::detail {
namespace {

// "d=2.500000 m [m/s]" -> 2.5 (the older surface receivers' column); nullopt for other names,
// and for a distance that is not finite ("d=-inf m [m/s]": no receiver the engine places, and
// its rows, sorted by distance, went out as -inf; found by the post fuzz target).
std::optional<double> distance_column(const std::string& name) {
  const std::string head = "d=", tail = " m [m/s]";
  if (name.size() <= head.size() + tail.size() || name.compare(0, head.size(), head) != 0 ||
      name.compare(name.size() - tail.size(), tail.size(), tail) != 0)
    return std::nullopt;
  const char* first = name.data() + head.size();
  const char* last = name.data() + name.size() - tail.size();
  double d = 0.0;
  const auto [ptr, ec] = std::from_chars(first, last, d);
  if (ec != std::errc() || ptr != last || !std::isfinite(d)) return std::nullopt;
  return d;
}

// "d=2.5 m" -> 2.5 (the name the engine gives a distance receiver, run_spec.cpp).
std::optional<double> distance_name(const std::string& name) {
  return distance_column(name + " [m/s]");
}

std::string distance_label(double d) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "d=%g m", d);  // as engine/scenario/src/run_spec.cpp
  return buf;
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

std::optional<json> read_summary(const fs::path& dir) {
  const fs::path file = dir / "summary.json";
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(file, ec))) return std::nullopt;
  if (const std::string problem = input_file_problem(file, kMaxResultJsonBytes); !problem.empty())
    throw std::runtime_error("summary.json in " + quoted(dir) + " " + problem +
                             ": rumble post reads the summary.json a run wrote, a regular file "
                             "of at most 64 MiB; rerun the scenario into the directory");
  const std::string text = read_input_file(file, kMaxResultJsonBytes);
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    throw std::runtime_error("summary.json in " + quoted(dir) + " is not valid JSON (" + e.what() +
                             "); the run was cut while writing it. Rerun the scenario");
  }
}

// Positions from summary.json's "ppv" entries: by name (probes) or in column order (distances).
void place_receivers(std::vector<Receiver>& receivers, bool probes, const fs::path& dir) {
  const std::optional<json> summary = read_summary(dir);
  const json* ppv = nullptr;
  if (summary && summary->contains("ppv") && (*summary)["ppv"].is_array()) ppv = &(*summary)["ppv"];
  auto get = [](const json& e, const char* key, double fallback) {
    return e.contains(key) && e[key].is_number() ? e[key].get<double>() : fallback;
  };
  for (std::size_t r = 0; r < receivers.size(); ++r) {
    Receiver& rx = receivers[r];
    const json* entry = nullptr;
    if (ppv && probes) {
      for (const json& e : *ppv)
        if (e.contains("name") && e["name"].is_string() && e["name"] == rx.name) entry = &e;
    } else if (ppv && r < ppv->size()) {
      entry = &(*ppv)[r];
    }
    if (entry) {
      rx.distance = get(*entry, "distance_m", rx.distance);
      rx.x = get(*entry, "x_m", rx.x);
      rx.depth = get(*entry, "depth_m", rx.depth);
      rx.resolved_f = get(*entry, "resolved_f_hz", kNaN);
    }
    if (std::isnan(rx.distance)) {
      if (const auto d = distance_name(rx.name)) rx.distance = *d;
    }
    if (std::isnan(rx.distance)) {
      throw std::runtime_error(
          (summary ? "summary.json in " + quoted(dir) + " has no \"ppv\" entry with \"name\": \"" +
                         rx.name + "\" and \"distance_m\""
                   : "summary.json is missing in " + quoted(dir)) +
          ", so the distance of receiver '" + rx.name +
          "' from the track is unknown. Post-process a complete results directory (rerun the "
          "scenario if summary.json was lost)");
    }
  }
}

// The run's status as its summary.json gives it ("" when it does not say).
std::string run_status(const fs::path& dir) {
  const std::optional<json> summary = read_summary(dir);
  return summary && summary->contains("status") && (*summary)["status"].is_string()
             ? (*summary)["status"].get<std::string>()
             : "";
}

}  // namespace

std::string list_names(const std::vector<std::string>& names, std::size_t max) {
  std::string out;
  for (std::size_t i = 0; i < names.size() && i < max; ++i)
    out += (i ? ", '" : "'") + names[i] + "'";
  if (names.size() > max) out += ", ... (" + std::to_string(names.size()) + " in all)";
  return out.empty() ? "none" : out;
}

RunRecord read_run(const fs::path& dir) {
  if (!fs::is_directory(dir))
    throw std::runtime_error("results directory " + quoted(dir) +
                             " does not exist or is not a directory; give the outputs.directory "
                             "of a run (e.g. scenarios/paper/results/...)");
  const fs::path file = dir / "receivers.csv";
  if (!fs::exists(file))
    throw std::runtime_error("no receivers.csv in " + quoted(dir) +
                             ": the run recorded no receivers. Add receivers to the scenario "
                             "(outputs.receivers, docs/scenario.md) and rerun it");
  RunRecord run;
  run.table = read_csv(file);
  const CsvTable& t = run.table;
  const std::string where = "receivers.csv in " + quoted(dir);
  // Probe receivers: "<name> vz [m/s]" with its vx and vy siblings.
  for (const std::string& col : t.names) {
    if (!ends_with(col, " vz [m/s]")) continue;
    Receiver rx;
    rx.name = col.substr(0, col.size() - std::string(" vz [m/s]").size());
    for (int c = 0; c < 3; ++c) {
      const std::string want = rx.name + " " + kComponents[c] + " [m/s]";
      rx.column[c] = t.find(want);
      if (!rx.column[c])
        throw std::runtime_error(where + " has no column '" + want + "' (it has '" + col +
                                 "'); the file is incomplete or was edited. Rerun the scenario "
                                 "(outputs.receivers lists the receivers)");
    }
    run.receivers.push_back(rx);
  }
  if (!run.receivers.empty()) {
    run.form = "probes";
  } else {
    for (std::size_t c = 0; c < t.names.size(); ++c) {
      if (const auto d = distance_column(t.names[c])) {
        Receiver rx;
        rx.name = distance_label(*d);
        rx.distance = *d;
        rx.column[2] = c;
        run.receivers.push_back(rx);
      }
    }
    run.form = "distances";
  }
  if (run.receivers.empty())
    throw std::runtime_error(where +
                             " has no receiver velocity column: expected '<name> vz [m/s]' "
                             "or 'd=<distance> m [m/s]', found " +
                             list_names(t.names) +
                             ". Rerun with receivers in the scenario (outputs.receivers)");
  place_receivers(run.receivers, run.form == "probes", dir);
  return run;
}

void cut_at_divergence(RunRecord& run, std::vector<std::string>& warnings, const fs::path& dir) {
  CsvTable& t = run.table;
  std::size_t first_bad = t.time.size();
  std::string column;
  for (const Receiver& rx : run.receivers)
    for (const auto& c : rx.column) {
      if (!c) continue;
      const std::vector<double>& v = t.columns[*c];
      for (std::size_t i = 0; i < first_bad; ++i)
        if (!std::isfinite(v[i])) {
          first_bad = i;
          column = t.names[*c];
          break;
        }
    }
  if (first_bad == t.time.size()) return;
  if (const std::string status = run_status(dir); status == "completed")
    throw std::runtime_error(
        "receivers.csv in " + quoted(dir) + ": column '" + column + "' is not finite at t = " +
        number_text(t.time[first_bad], 9) + " s (data row " + std::to_string(first_bad + 1) +
        "), but summary.json says the run completed, which writes finite numbers only: the "
        "file was damaged or edited after the run. Rerun the scenario");
  if (first_bad < 2)
    throw std::runtime_error(
        "receivers.csv in " + quoted(dir) + ": column '" + column +
        "' is not finite from its first rows (t = " + number_text(t.time[first_bad], 9) +
        " s); the run diverged at once. Check the run's summary.json "
        "status and stability, then rerun with a smaller macro step");
  warnings.push_back("receivers.csv: '" + column +
                     "' is not finite from t = " + number_text(t.time[first_bad], 9) +
                     " s (the run diverged); the indicators use the " + std::to_string(first_bad) +
                     " rows before it");
  t.time.resize(first_bad);
  for (std::vector<double>& v : t.columns) v.resize(first_bad);
}

}  // namespace rumble::post::detail
