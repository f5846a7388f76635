// `rumble soil-frf FILE [FILE...]`: driving-point and transfer receptances of each scenario's
// soil at its footprints, one CSV per soil in one directory, plotted together.
#include <iostream>

#include "analysis/soil_frf.hpp"
#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "cli/plot_script.hpp"
#include "cli/scenario_prepare.hpp"
#include "core/errors.hpp"
#include "plugin/instance.hpp"
#include "run/run_scenario.hpp"

namespace rumble::cli {

int soil_frf_command(const std::vector<std::string>& args) {
  const Arguments a(args, {"no-plot"}, {"fmin", "fmax", "points", "terms", "output"});
  if (a.positional().empty()) {
    throw UsageError(
        "usage: rumble soil-frf FILE [FILE...] [--fmin 1] [--fmax 100] [--points 100] "
        "[--terms 2] [--output DIR] [--no-plot]");
  }
  const double f_min = a.number("fmin", 1.0), f_max = a.number("fmax", 100.0);
  const int points = static_cast<int>(a.number("points", 100));
  const int terms = static_cast<int>(a.number("terms", 2));
  if (!(f_min > 0.0) || !(f_max > f_min) || points < 2 || terms < 0) {
    throw UsageError("need 0 < --fmin < --fmax, --points >= 2 and --terms >= 0");
  }
  const std::vector<double> frequency = log_frequencies(f_min, f_max, points);
  std::filesystem::path out_dir;
  PluginRegistry registry;
  for (const std::string& file : a.positional()) {
    const auto doc = prepare_scenario(file, registry, scenario::Format::kText);
    if (!doc) return kExitConfig;
    if (out_dir.empty()) {
      out_dir = a.value("output") ? std::filesystem::path(*a.value("output"))
                                  : scenario::results_directory(doc->json, doc->path) / "soil_frf";
      std::filesystem::create_directories(out_dir);
    }
    const ScenarioSoil s = soil_on_footprints(*doc, registry);
    SoilFrf frf;
    frf.label = s.type->type_name + " (" + doc->path.stem().string() + ")";
    if (!soil_frf(*s.soil, s.layout.size(), frequency, static_cast<std::size_t>(terms), frf)) {
      throw ConfigError(file + ": /soil/type: soil type '" + s.type->type_name +
                        "' offers no frequency response; use a soil that does (fem, winkler, clm)");
    }
    const auto csv = out_dir / (doc->path.stem().string() + "_" + s.type->type_name + ".csv");
    write_frf_csv(csv, frf);
    std::cout << "wrote " << csv.string() << '\n';
  }
  if (!a.flag("no-plot")) run_plot_script("plot_frf.py", out_dir);
  return kExitOk;
}

}  // namespace rumble::cli
