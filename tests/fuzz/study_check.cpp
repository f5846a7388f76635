#include "study_check.hpp"

#include <climits>
#include <exception>
#include <filesystem>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "core/errors.hpp"
#include "fuzz_support.hpp"
#include "plugin/registry.hpp"
#include "scenario/check_file.hpp"
#include "scenario/scenario.hpp"
#include "study/expansion.hpp"
#include "study/run_key.hpp"
#include "study/study_file.hpp"

namespace rumble::fuzz {
namespace {

namespace fs = std::filesystem;

/// How many of a study's runs get the per-run check: a study of 1e4 runs is 1e4 scenario
/// checks (seconds), and the runs differ only by their patches, which the first ones and the
/// last (an explicit run when there are any) have as much as any.
constexpr std::size_t kRunsChecked = 4;

/// The scratch folder with the scenarios a study may name, made once.
const fs::path& study_folder() {
  static const fs::path dir = [] {
    const fs::path d = scratch_dir("study");
    const std::string minimal =
        read_file(source_dir() / "tests" / "scenario" / "valid" / "minimal.json");
    for (const char* name : {"base.json", "other.json", "scenario.json"})
      write_file(d / name, minimal);
    write_file(d / "track_on_fem_soil.json", read_file(source_dir() / "scenarios" / "paper" /
                                                       "study" / "track_on_fem_soil.json"));
    return d;
  }();
  return dir;
}

/// A name `rumble study` can make the results directory of: the characters of filesystem_safe,
/// at most NAME_MAX bytes.
bool directory_name(const std::string& name) {
  if (name.empty() || name.size() > NAME_MAX) return false;
  for (const char c : name) {
    const bool alnum = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    if (!alnum && c != '.' && c != '_' && c != '-') return false;
  }
  return name.front() != '.' && name.front() != '-' && name.front() != '_';
}

/// prepare_runs' check of one run with --no-load; its key when it is valid.
std::string check_run(const study::StudyFile& s, const study::PlannedRun& run,
                      std::set<std::string>& keys) {
  std::vector<scenario::Override> set = study::overrides(run, s.path);
  PluginRegistry registry;
  scenario::CheckOptions options;
  options.load_plugins = false;       // no plugin library named by a patch is loaded
  options.results_directory = false;  // each run writes to its own --output directory
  try {
    const scenario::CheckedScenario c =
        scenario::check_scenario_file(run.scenario, set, registry, options);
    if (!c.doc && c.diagnostics.empty()) return "run " + run.name + " unread without a diagnostic";
    if (c.doc) {
      if (std::string bad = check_diagnostics(c.doc->text, c.diagnostics); !bad.empty())
        return "run " + run.name + ": " + bad;
    }
    if (c.ok()) {
      const std::string key = study::run_key(run, *c.doc, registry);
      if (key.size() != 64) return "run " + run.name + " has the key \"" + key + "\"";
      if (!keys.insert(key).second) return "run " + run.name + " has another run's key";
    }
  } catch (const ConfigError& e) {  // a patch that cannot be applied: the run is not valid
    const std::string message = e.what();
    if (message.rfind(s.path.string() + ": /", 0) != 0)
      return "a patch refused without naming the study file and its place: " + message;
  }
  return "";
}

std::string check_study(std::string_view text) {
  const fs::path& folder = study_folder();
  const fs::path file = folder / "study.json";
  const std::string before = tree_listing(folder);

  std::vector<scenario::Diagnostic> diagnostics;
  std::optional<scenario::Document> doc =
      scenario::parse_document(file, std::string(text), diagnostics);
  if (!doc) {
    if (diagnostics.empty()) return "refused without a diagnostic";
    if (std::string bad = check_diagnostics(text, diagnostics); !bad.empty()) return bad;
    return check_reports(nullptr, file, diagnostics);
  }
  std::optional<study::StudyFile> s = study::read_study(*doc, diagnostics);
  if (!s && diagnostics.empty()) return "study refused without a diagnostic";
  if (s && !diagnostics.empty()) return "study read with a diagnostic: " + diagnostics[0].message;
  std::vector<study::PlannedRun> runs;
  std::error_code ec;
  bool output_existed = false;
  if (s) {
    output_existed = fs::exists(fs::symlink_status(s->output, ec));
    runs = study::expand(*s, diagnostics);
    double product = s->axes.empty() ? 0.0 : 1.0;
    for (const study::Axis& a : s->axes) product *= static_cast<double>(a.values.size());
    const double planned = product + static_cast<double>(s->runs.size());
    if (planned > study::kMaxStudyRuns) return "a study of " + std::to_string(planned) + " runs";
    if (runs.empty() != !diagnostics.empty())
      return std::to_string(runs.size()) + " runs and " + std::to_string(diagnostics.size()) +
             " diagnostics after expansion";
    if (!runs.empty() && static_cast<double>(runs.size()) != planned)
      return std::to_string(runs.size()) + " runs expanded of " + std::to_string(planned);
    for (const study::PlannedRun& r : runs)
      if (!directory_name(r.name))
        return "run \"" + r.name.substr(0, 300) + "\" (" + std::to_string(r.name.size()) +
               " bytes) cannot name its results directory";
    if (auto outside = study::output_outside_folder(*s)) {
      if (outside->message.empty()) return "the output folder's finding has no message";
      diagnostics.push_back(std::move(*outside));
    }
  }
  if (std::string bad = check_diagnostics(text, diagnostics); !bad.empty()) return bad;
  if (std::string bad = check_reports(&*doc, file, diagnostics); !bad.empty()) return bad;

  if (s && !runs.empty()) {
    std::set<std::string> keys;
    for (std::size_t i = 0; i < runs.size(); ++i) {
      if (i >= kRunsChecked - 1 && i + 1 != runs.size()) continue;
      if (std::string bad = check_run(*s, runs[i], keys); !bad.empty()) return bad;
    }
  }
  if (tree_listing(folder) != before) return "the study wrote into its folder";
  if (s && fs::exists(fs::symlink_status(s->output, ec)) != output_existed)
    return "the study made its output folder " + s->output.string();
  return "";
}

}  // namespace

std::string check_study_text(std::string_view text) {
  try {
    return check_study(text);
  } catch (const std::exception& e) {
    return std::string("exception escaped: ") + e.what();
  }
}

}  // namespace rumble::fuzz
