#include "study/expansion.hpp"

#include <map>

#include "scenario/value_text.hpp"

namespace rumble::study {
namespace {

using ojson = nlohmann::ordered_json;

ojson patch_json(const std::vector<Patch>& patches) {
  ojson out = ojson::object();
  for (const Patch& p : patches) out[p.pointer] = ojson::parse(p.value.dump());
  return out;
}

}  // namespace

std::vector<PlannedRun> expand(const StudyFile& study,
                               std::vector<scenario::Diagnostic>& diagnostics) {
  std::vector<PlannedRun> runs;
  if (!study.axes.empty()) {
    // What each value adds to a run's entry, made once: made per run, the 4e4 patch copies of a
    // study at the run limit took seconds (the study fuzz target's slowest input).
    std::vector<std::vector<ojson>> value_entries(study.axes.size());
    for (std::size_t a = 0; a < study.axes.size(); ++a)
      for (const AxisValue& v : study.axes[a].values)
        value_entries[a].push_back({{"value", v.name}, {"set", patch_json(v.patches)}});
    // Odometer over the value indices, the last axis fastest.
    std::vector<std::size_t> index(study.axes.size(), 0);
    for (;;) {
      PlannedRun run;
      run.scenario = study.scenario;
      run.entry = ojson::object();
      for (std::size_t a = 0; a < study.axes.size(); ++a) {
        const Axis& axis = study.axes[a];
        const AxisValue& v = axis.values[index[a]];
        run.name += (a == 0 ? "" : "-") + v.name;
        run.axis_values[axis.name] = v.name;
        run.patches.insert(run.patches.end(), v.patches.begin(), v.patches.end());
        run.entry[axis.name] = value_entries[a][index[a]];
      }
      runs.push_back(std::move(run));
      std::size_t a = study.axes.size();
      while (a > 0 && ++index[a - 1] == study.axes[a - 1].values.size()) index[--a] = 0;
      if (a == 0) break;
    }
  }
  for (const ExplicitRun& e : study.runs) {
    PlannedRun run;
    run.name = e.name;
    run.scenario = e.scenario;
    run.patches = e.set;
    run.entry = e.entry;
    run.source = e.source;
    runs.push_back(std::move(run));
  }
  std::map<std::string, const PlannedRun*> seen;
  bool duplicates = false;
  const auto describe = [](const PlannedRun& r) {
    if (!r.source.empty()) return "the run at " + r.source;
    std::string values;
    for (const auto& [axis, value] : r.axis_values.items())
      values += (values.empty() ? "" : ", ") + axis + " = " + value.get<std::string>();
    return "the axes (" + values + ")";
  };
  for (const PlannedRun& r : runs) {
    const auto [it, fresh] = seen.emplace(r.name, &r);
    if (fresh) continue;
    duplicates = true;
    diagnostics.push_back(scenario::finding(
        r.source.empty() ? "/axes" : r.source + "/name",
        "two runs are named " + scenario::quote_name(r.name) + ": " + describe(*it->second) +
            " and " + describe(r),
        "run names name their results directories; rename a run or an axis value"));
  }
  if (duplicates) runs.clear();
  return runs;
}

std::vector<scenario::Override> overrides(const PlannedRun& run,
                                          const std::filesystem::path& study_file) {
  std::vector<scenario::Override> out;
  for (const Patch& p : run.patches) {
    scenario::Override o;
    o.pointer = p.pointer;
    o.value = p.value;
    o.label = study_file.string() + ": " + p.source + ": " + p.pointer + " = " +
              scenario::short_json(p.value);
    o.origin = "the study, " + p.source;
    out.push_back(std::move(o));
  }
  return out;
}

}  // namespace rumble::study
