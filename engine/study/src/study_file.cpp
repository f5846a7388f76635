#include "study/study_file.hpp"

#include <algorithm>
#include <set>
#include <sstream>

#include "scenario/did_you_mean.hpp"
#include "scenario/json_position.hpp"
#include "scenario/overrides.hpp"
#include "scenario/run_spec.hpp"
#include "scenario/value_text.hpp"

namespace rumble::study {
namespace {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;
using scenario::Diagnostic;
using scenario::finding;

const std::vector<std::string> kTopKeys = {"study_version", "name", "description", "scenario",
                                           "output",        "axes", "runs",        "jobs"};
const std::vector<std::string> kAxisKeys = {"name", "values"};
const std::vector<std::string> kRunKeys = {"name", "scenario", "set"};

std::string got(const ojson& v) {
  return "got " + scenario::short_json(nlohmann::json::parse(v.dump()));
}

std::string member(const std::string& parent, const std::string& key) {
  return parent + "/" + scenario::escape_pointer_token(key);
}

class Reader {
 public:
  Reader(const fs::path& folder, std::vector<Diagnostic>& d) : folder_(folder), d_(d) {}

  void error(std::string pointer, std::string message, std::string hint = "") {
    d_.push_back(finding(std::move(pointer), std::move(message), std::move(hint)));
  }

  /// Unknown keys of an object, each with a "did you mean" and the keys allowed there.
  void known_keys(const ojson& object, const std::string& at, const std::vector<std::string>& keys,
                  const char* what) {
    for (const auto& [key, value] : object.items()) {
      if (std::find(keys.begin(), keys.end(), key) != keys.end()) continue;
      const auto close = scenario::closest_match(key, keys);
      error(member(at, key), "unknown key " + scenario::quote_name(key) + " in " + what,
            (close ? "did you mean \"" + *close + "\"? " : std::string()) + "keys of " + what +
                ": " + scenario::join(keys));
    }
  }

  std::optional<std::string> string(const ojson& object, const std::string& at,
                                    const std::string& key, bool required, const char* fix) {
    if (!object.contains(key)) {
      if (required) error(at, "missing \"" + key + "\"", fix);
      return std::nullopt;
    }
    const ojson& v = object[key];
    if (!v.is_string() || v.get<std::string>().empty()) {
      error(member(at, key), "must be a non-empty string, " + got(v), fix);
      return std::nullopt;
    }
    return v.get<std::string>();
  }

  /// A run, axis or value name that becomes (part of) a directory name.
  bool safe_name(const std::string& name, const std::string& at, const char* what) {
    if (filesystem_safe(name)) return true;
    error(at, what + std::string(" ") + scenario::quote_name(name) + " cannot name a directory",
          "use 1 to 100 letters, digits, '.', '_' or '-', starting with a letter or digit");
    return false;
  }

  /// A scenario file named at `at`, resolved against the study file's folder; must exist.
  std::optional<fs::path> scenario_file(const std::string& text, const std::string& at) {
    const fs::path p = fs::path(text).is_absolute() ? fs::path(text) : folder_ / text;
    std::error_code ec;
    if (!fs::is_regular_file(p, ec)) {
      error(at, "scenario file " + p.lexically_normal().string() + " not found",
            "paths are relative to the study file's folder (" +
                (folder_.empty() ? std::string(".") : folder_.string()) + ")");
      return std::nullopt;
    }
    return p;
  }

  /// {"/pointer": value, ...} at `at`.
  std::vector<Patch> patches(const ojson& object, const std::string& at, const char* what) {
    std::vector<Patch> out;
    if (!object.is_object()) {
      error(at,
            std::string(what) + " must be an object of JSON pointers and values, " + got(object),
            "e.g. {\"/soil/params/E\": 1.55e8, \"/coupling/type\": \"jacobi\"}");
      return out;
    }
    for (const auto& [pointer, value] : object.items()) {
      const std::string source = member(at, pointer);
      if (const std::string problem = scenario::pointer_problem(pointer); !problem.empty()) {
        error(source, problem, "a key here names the scenario value to replace");
        continue;
      }
      out.push_back({pointer, nlohmann::json::parse(value.dump()), source});
    }
    return out;
  }

 private:
  fs::path folder_;
  std::vector<Diagnostic>& d_;
};

/// The study's own keys: its version, name, description, output folder and jobs.
void read_study_header(Reader& r, const ojson& j, const fs::path& path, StudyFile& s) {
  if (!j.contains("study_version")) {
    r.error("", "missing \"study_version\"", "add \"study_version\": 1 at the top");
  } else if (j["study_version"] != kStudyVersion) {
    r.error("/study_version", "must be 1, " + got(j["study_version"]),
            "this rumble reads study files of version 1");
  }
  s.name =
      r.string(j, "", "name", false, "a short title of the study").value_or(path.stem().string());
  s.description = r.string(j, "", "description", false, "what the study is for").value_or("");
  const auto output = r.string(j, "", "output", false,
                               "the folder of the study's results, relative to the study file");
  s.output_text = output.value_or("results/" + path.stem().string());
  s.output = path.parent_path() / s.output_text;
  if (j.contains("jobs")) {
    const ojson& v = j["jobs"];
    if (!v.is_number_integer() || v.get<long long>() < 1 || v.get<long long>() > 1024) {
      r.error("/jobs", "must be an integer from 1 to 1024, " + got(v),
              "the number of runs at once; leave it out to use half the cores");
    } else {
      s.jobs = v.get<int>();
    }
  }
}

/// The axis at `at`, its name not among `names` (which it joins); nullopt when not an object.
std::optional<Axis> read_axis(Reader& r, const ojson& a, const std::string& at,
                              std::set<std::string>& names) {
  if (!a.is_object()) {
    r.error(at, "an axis must be an object {\"name\", \"values\"}, " + got(a));
    return std::nullopt;
  }
  r.known_keys(a, at, kAxisKeys, "an axis");
  Axis axis;
  if (const auto name = r.string(a, at, "name", true, "e.g. \"name\": \"soil\"")) {
    axis.name = *name;
    if (r.safe_name(*name, at + "/name", "axis name") && !names.insert(*name).second) {
      r.error(at + "/name", "axis name " + scenario::quote_name(*name) + " is used twice",
              "give each axis its own name");
    }
  }
  if (!a.contains("values")) {
    r.error(at, "missing \"values\"",
            "e.g. \"values\": {\"soft\": {\"/soil/params/E\": 1e7}, \"stiff\": {...}}");
  } else if (!a["values"].is_object() || a["values"].empty()) {
    r.error(at + "/values", "must be an object with at least one named value, " + got(a["values"]),
            "e.g. {\"soft\": {\"/soil/params/E\": 1e7}, \"stiff\": {\"/soil/params/E\": "
            "7.5e8}}");
  } else {
    for (const auto& [value_name, patch] : a["values"].items()) {
      const std::string vat = member(at + "/values", value_name);
      r.safe_name(value_name, vat, "value name");
      axis.values.push_back({value_name, r.patches(patch, vat, "an axis value")});
    }
  }
  return axis;
}

/// "axes": each varies the base scenario, so the study must name one.
void read_axes(Reader& r, const ojson& axes, bool has_base, StudyFile& s) {
  if (!axes.is_array() || axes.empty()) {
    r.error("/axes", "must be a non-empty array of axes, " + got(axes),
            "e.g. [{\"name\": \"soil\", \"values\": {\"soft\": {\"/soil/params/E\": 1e7}}}]; "
            "leave \"axes\" out to list only \"runs\"");
    return;
  }
  if (!has_base) {
    r.error("/axes", "axes vary the base scenario, and the study names none",
            "add \"scenario\": \"FILE.json\" (relative to the study file)");
  }
  std::set<std::string> names;
  for (std::size_t i = 0; i < axes.size(); ++i) {
    if (auto axis = read_axis(r, axes[i], "/axes/" + std::to_string(i), names))
      s.axes.push_back(std::move(*axis));
  }
}

/// The listed run at `at`: its name, its scenario (the study's base when it names none) and its
/// patches; nullopt when not an object.
std::optional<ExplicitRun> read_listed_run(Reader& r, const ojson& e, const std::string& at,
                                           bool has_base, const StudyFile& s) {
  if (!e.is_object()) {
    r.error(at, "a run must be an object {\"name\", \"scenario\", \"set\"}, " + got(e));
    return std::nullopt;
  }
  r.known_keys(e, at, kRunKeys, "a run");
  ExplicitRun run;
  run.entry = e;
  run.source = at;
  if (const auto name = r.string(e, at, "name", true, "e.g. \"name\": \"soft-fine-step\"")) {
    run.name = *name;
    r.safe_name(*name, at + "/name", "run name");
  }
  if (const auto file =
          r.string(e, at, "scenario", false, "a scenario file, relative to the study file")) {
    if (const auto p = r.scenario_file(*file, at + "/scenario")) run.scenario = *p;
  } else if (!e.contains("scenario")) {
    run.scenario = s.scenario;
    if (!has_base) {
      r.error(at, "this run names no scenario, and the study has no base scenario",
              "add \"scenario\": \"FILE.json\" to the run or to the study");
    }
  }
  if (e.contains("set")) run.set = r.patches(e["set"], at + "/set", "\"set\"");
  return run;
}

void read_listed_runs(Reader& r, const ojson& runs, bool has_base, StudyFile& s) {
  if (!runs.is_array() || runs.empty()) {
    r.error("/runs", "must be a non-empty array of runs, " + got(runs),
            "e.g. [{\"name\": \"fine-step\", \"set\": {\"/time/macro_step\": 1e-4}}]; leave "
            "\"runs\" out to run only the product of the axes");
    return;
  }
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (auto run = read_listed_run(r, runs[i], "/runs/" + std::to_string(i), has_base, s))
      s.runs.push_back(std::move(*run));
  }
}

/// Counted before anything is expanded: 8 axes of 20 values were 2.6e10 runs, and even
/// --dry-run died of std::bad_alloc expanding them.
void check_run_count(Reader& r, const StudyFile& s) {
  double product = s.axes.empty() ? 0.0 : 1.0;
  for (const Axis& axis : s.axes) product *= static_cast<double>(axis.values.size());
  if (const double total = product + static_cast<double>(s.runs.size()); total > kMaxStudyRuns) {
    std::ostringstream m;
    m << "the study has " << total << " runs (";
    for (std::size_t i = 0; i < s.axes.size(); ++i)
      m << (i ? " x " : "") << s.axes[i].values.size();
    m << (s.axes.empty() ? "" : " from the axes") << (s.runs.empty() ? "" : ", ")
      << (s.runs.empty() ? "" : std::to_string(s.runs.size()) + " listed") << "), more than the "
      << kMaxStudyRuns << " a study holds";
    r.error(s.axes.empty() ? "/runs" : "/axes", m.str(),
            "remove axes or values, or split the study into several");
  }
}

/// A product run's name is its value names joined, and names its results directory: three
/// axes of 100-character names made a name no file system takes (NAME_MAX), which --dry-run
/// passed; the study then stopped at the first such run, "File name too long", after the runs
/// before it had run.
void check_run_name_length(Reader& r, const StudyFile& s) {
  std::size_t longest = 0;
  std::string lengths;  // "100 + 100 + 100"
  for (const Axis& axis : s.axes) {
    std::size_t most = 0;
    for (const AxisValue& value : axis.values) most = std::max(most, value.name.size());
    longest += (lengths.empty() ? 0 : 1) + most;
    lengths += (lengths.empty() ? "" : " + ") + std::to_string(most);
  }
  if (longest > kMaxRunNameBytes) {
    r.error("/axes",
            "the axes' product has run names of up to " + std::to_string(longest) +
                " characters (the longest value name of each axis, " + lengths +
                ", joined by '-'), more than the " + std::to_string(kMaxRunNameBytes) +
                " a results folder's name may have",
            "shorten the value names, or use fewer axes");
  }
}

}  // namespace

std::optional<Diagnostic> output_outside_folder(const StudyFile& study) {
  return scenario::outside_folder({"/output", "study file", "pass --allow-outside-results"},
                                  study.path, study.output_text);
}

bool filesystem_safe(const std::string& name) {
  if (name.empty() || name.size() > 100) return false;
  const auto alnum = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
  };
  if (!alnum(name[0])) return false;
  for (const char c : name) {
    if (!alnum(c) && c != '.' && c != '_' && c != '-') return false;
  }
  return true;
}

std::optional<StudyFile> read_study(const scenario::Document& doc,
                                    std::vector<Diagnostic>& diagnostics) {
  const std::size_t errors_before = diagnostics.size();
  Reader r(doc.path.parent_path(), diagnostics);
  // Read again in the file's order: axis values expand in the order they are written.
  const ojson j = ojson::parse(doc.text);
  if (!j.is_object()) {
    r.error("", "a study file is one JSON object, " + got(j),
            "e.g. {\"study_version\": 1, \"scenario\": \"base.json\", \"axes\": [...]}");
    return std::nullopt;
  }
  r.known_keys(j, "", kTopKeys, "a study");
  StudyFile s;
  s.path = doc.path;
  read_study_header(r, j, doc.path, s);
  if (const auto base = r.string(j, "", "scenario", false,
                                 "the base scenario file, relative to the study file")) {
    if (const auto p = r.scenario_file(*base, "/scenario")) s.scenario = *p;
  }
  const bool has_base = j.contains("scenario");
  if (j.contains("axes")) read_axes(r, j["axes"], has_base, s);
  if (j.contains("runs")) read_listed_runs(r, j["runs"], has_base, s);
  check_run_count(r, s);
  check_run_name_length(r, s);
  if (!j.contains("axes") && !j.contains("runs")) {
    r.error("", "the study has no runs",
            "add \"axes\" (the product of their values is run) or \"runs\" (a list), or both");
  }
  if (diagnostics.size() != errors_before) return std::nullopt;
  return s;
}

}  // namespace rumble::study
