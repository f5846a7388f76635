// `rumble soil-frf FILE [FILE...]`: driving-point and transfer receptances of each scenario's
// soil at its footprints, one CSV per soil in one directory, plotted together. The directory is a
// results directory like a run's (results/results_directory.hpp): locked while written, its files
// listed in a manifest, so a rerun replaces its own files and two at once do not interleave.
#include <cmath>
#include <iostream>
#include <optional>

#include "analysis/soil_frf.hpp"
#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "cli/plot_script.hpp"
#include "cli/scenario_prepare.hpp"
#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "core/number_text.hpp"
#include "parallel/mpi_session.hpp"
#include "plugin/instance.hpp"
#include "results/results_directory.hpp"
#include "run/run_scenario.hpp"

namespace rumble::cli {

int soil_frf_command(const std::vector<std::string>& args) {
  const Arguments a(args, {"no-plot", "overwrite", "allow-outside-results"},
                    {"fmin", "fmax", "points", "terms", "output"});
  if (a.positional().empty()) {
    throw UsageError(
        "usage: rumble soil-frf FILE [FILE...] [--fmin 1] [--fmax 100] [--points 100] "
        "[--terms 2] [--output DIR] [--overwrite] [--allow-outside-results] [--no-plot]");
  }
  const double f_min = a.number("fmin", 1.0), f_max = a.number("fmax", 100.0);
  const long long points = a.integer("points", 100, 2, 100000);
  const long long terms = a.integer("terms", 2, 0, 1000);
  if (!(f_min > 0.0) || !(f_max > f_min) || !std::isfinite(f_max)) {
    throw UsageError("need 0 < --fmin < --fmax (finite frequencies in Hz), got --fmin " +
                     number_text(f_min) + " and --fmax " + number_text(f_max));
  }
  const auto output = a.directory("output", "one CSV per scenario");
  const std::vector<double> frequency = log_frequencies(f_min, f_max, static_cast<int>(points));
  std::optional<ResultsDirectory> results;
  PluginRegistry registry;
  for (const std::string& file : a.positional()) {
    BuiltSoils built;  // the soil validation builds is the one measured: built once
    scenario::CheckOptions check = kNotARun;
    if (!results)  // the first scenario's outputs.directory holds soil_frf/
      check_results_directory(check, output.has_value(), a.flag("allow-outside-results"));
    check.keep_soils = &built;
    check.ranks = parallel::world_size();  // a distributed soil split so has no whole operator
    check.whole_soil = {"rumble soil-frf", "the soil's receptance", "frequency_response"};
    const auto doc = prepare_scenario(file, registry, scenario::Format::kText, {}, check);
    if (!doc) return kExitConfig;
    if (!results) {
      const std::filesystem::path out_dir =
          output ? std::filesystem::path(*output)
                 : scenario::results_directory(doc->json, doc->path) / "soil_frf";
      // The first scenario owns the directory; the others make the set (a rerun with the same
      // files replaces its own CSVs, another set needs --overwrite).
      std::vector<std::string> others(a.positional().begin() + 1, a.positional().end());
      for (std::string& o : others) {
        std::error_code ec;
        o = "+" + std::filesystem::weakly_canonical(std::filesystem::absolute(o), ec).string();
      }
      results.emplace(out_dir, doc->path, a.flag("overwrite"), others);
    }
    const ScenarioSoil s = soil_on_footprints(*doc, registry, &built);
    install_interrupt_handler();  // soil_frf() honours it: says where it stopped
    SoilFrf frf;
    frf.label = s.type->type_name + " (" + doc->path.stem().string() + ")";
    if (!soil_frf(*s.soil, s.layout.size(), frequency, static_cast<std::size_t>(terms), frf)) {
      throw ConfigError(file + ": /soil/type: soil type '" + s.type->type_name +
                        "' offers no frequency response; use a soil that does (fem, winkler, clm)");
    }
    const auto csv = results->file(doc->path.stem().string() + "_" + s.type->type_name + ".csv");
    write_frf_csv(csv, frf);
    std::cout << "wrote " << csv.lexically_normal().string() << '\n';
  }
  if (!a.flag("no-plot")) run_plot_script("plot_frf.py", results->path());
  return kExitOk;
}

}  // namespace rumble::cli
