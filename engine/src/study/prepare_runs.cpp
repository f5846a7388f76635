#include "study/prepare_runs.hpp"

#include <ostream>

#include "core/errors.hpp"
#include "plugin/registry.hpp"
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
