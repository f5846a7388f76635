#include "study/prepare_runs.hpp"

#include <sys/stat.h>

#include <ostream>

#include "core/errors.hpp"
#include "plugin/registry.hpp"
#include "results/new_file.hpp"
#include "scenario/check_file.hpp"
#include "scenario/report.hpp"
#include "study/run_key.hpp"

namespace rumble::study {
namespace {

namespace fs = std::filesystem;

/// The child's arguments: run FILE --set P=V ... --output DIR --no-progress --overwrite.
std::vector<std::string> child_command(const RunRecord& r, bool size_confirmed) {
  std::vector<std::string> c{"run", fs::absolute(r.run.scenario).string()};
  for (const Patch& p : r.run.patches) {
    c.push_back("--set");
    c.push_back(p.pointer + "=" +
                p.value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
  }
  // --overwrite: run.log, written by the study, stands in the directory before the run starts.
  c.insert(c.end(), {"--output", fs::absolute(r.results).string(), "--no-progress", "--overwrite"});
  if (size_confirmed) c.push_back("--yes");
  return c;
}

/// Why a run's results cannot go to `dir` (inside the study's output folder): "" when it is
/// missing (made when the run starts) or a real directory. Anything else stands there in the
/// way, never followed nor removed: a symbolic link would take the run's results (and the
/// --overwrite the study gives the run) wherever it leads.
std::string not_a_run_directory(const fs::path& dir) {
  struct stat st {};
  if (::lstat(dir.c_str(), &st) != 0 || S_ISDIR(st.st_mode)) return "";
  return "its results directory " + dir.lexically_normal().string() + " is " + what_stands_at(dir) +
         "; a study writes each run's results into a real directory of its output folder and "
         "never through a link nor over what stands there: move it away";
}

}  // namespace

std::vector<RunRecord> prepare_runs(const StudyFile& study, std::vector<PlannedRun> runs,
                                    PluginRegistry& registry, std::ostream& report,
                                    bool size_confirmed) {
  scenario::CheckOptions options;
  options.size_confirmed = size_confirmed;
  options.results_directory = false;  // every run writes to its own --output directory
  std::vector<RunRecord> records;
  for (PlannedRun& run : runs) {
    RunRecord r;
    r.run = std::move(run);
    r.results = study.output / r.run.name;
    if (const std::string why = not_a_run_directory(r.results); !why.empty()) {
      r.state = RunState::kInvalid;
      r.message = "not valid: " + why;
      report << "study: run " << r.run.name << " is not valid:\n" << why << '\n';
      records.push_back(std::move(r));
      continue;
    }
    std::vector<scenario::Override> set = overrides(r.run, study.path);
    try {
      const scenario::CheckedScenario c =
          scenario::check_scenario_file(r.run.scenario, set, registry, options);
      if (c.ok()) {
        r.key = run_key(r.run, *c.doc, registry);
        r.command = child_command(r, size_confirmed);
      } else {
        r.state = RunState::kInvalid;
        for (const scenario::Diagnostic& d : c.diagnostics) {
          if (d.severity != scenario::Diagnostic::Severity::kError) continue;
          r.message = "not valid: " + (d.pointer.empty() ? "" : d.pointer + ": ") + d.message;
          break;
        }
        report << "study: run " << r.run.name << " is not valid:\n";
        scenario::print_diagnostics(report, c.doc ? &*c.doc : nullptr, r.run.scenario,
                                    c.diagnostics, scenario::Format::kText);
      }
    } catch (const ConfigError& e) {  // a patch that cannot be applied
      r.state = RunState::kInvalid;
      r.message = std::string("not valid: ") + e.what();
      report << "study: run " << r.run.name << " is not valid:\n" << e.what() << '\n';
    } catch (const PluginLoadError& e) {
      r.state = RunState::kInvalid;
      r.message = std::string("not valid: ") + e.what();
      report << "study: run " << r.run.name << " is not valid:\n" << e.what() << '\n';
    }
    records.push_back(std::move(r));
  }
  return records;
}

}  // namespace rumble::study
