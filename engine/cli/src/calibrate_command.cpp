// `rumble calibrate TARGET --model TYPE --params JSON [--fit a,b]`: fit a reduced soil's
// parameters to the receptance of the target scenario's soil over a frequency band, and report
// the fitted params (ready to paste into a scenario) and the residual.
#include <cmath>
#include <iostream>
#include <sstream>

#include "analysis/calibrate.hpp"
#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "cli/scenario_prepare.hpp"
#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "parallel/mpi_session.hpp"
#include "plugin/instance.hpp"
#include "results/new_file.hpp"

namespace rumble::cli {
int calibrate_command(const std::vector<std::string>& args) {
  const Arguments a(args, {},
                    {"model", "params", "fit", "fmin", "fmax", "points", "terms", "output"});
  if (a.positional().size() != 1 || !a.value("model")) {
    throw UsageError(
        "usage: rumble calibrate TARGET_SCENARIO --model TYPE [--params JSON] [--fit a,b,...] "
        "[--fmin 1] [--fmax 100] [--points 40] [--terms 2] [--output FILE]");
  }
  PluginRegistry registry;
  BuiltSoils built;  // the target soil validation builds is the one measured: built once
  scenario::CheckOptions check = kNotARun;
  check.keep_soils = &built;
  check.ranks = parallel::world_size();  // a distributed soil split so has no whole operator
  check.whole_soil = {"rumble calibrate", "the target soil's receptance", "frequency_response"};
  const auto doc =
      prepare_scenario(a.positional()[0], registry, scenario::Format::kText, {}, check);
  if (!doc) return kExitConfig;
  const std::string model_name = *a.value("model");
  const ComponentType* model = registry.find(RUMBLE_KIND_SOIL, model_name);
  if (model == nullptr) {
    throw UsageError("--model " + model_name + " is not a soil type; soil types: " + [&] {
      std::string s;
      for (const auto& n : registry.type_names(RUMBLE_KIND_SOIL)) s += (s.empty() ? "" : ", ") + n;
      return s;
    }());
  }
  const auto& target_soil = doc->json.at("soil");
  nlohmann::json start;
  if (a.value("params")) {
    try {
      start = nlohmann::json::parse(*a.value("params"));
    } catch (const nlohmann::json::exception& e) {
      throw UsageError(std::string("--params is not JSON: ") + e.what());
    }
  } else if (target_soil.at("type") == model_name) {
    start = target_soil.value("params", nlohmann::json::object());
  } else {
    throw UsageError("give the starting values of the model's params with --params '{...}'");
  }

  CalibrationProblem problem;
  problem.model = model;
  problem.base_params = start;
  problem.scenario_dir = doc->path.parent_path();
  const ScenarioSoil target = soil_on_footprints(*doc, registry, &built);
  install_interrupt_handler();  // soil_frf() honours it: says where it stopped
  problem.layout = target.layout;
  problem.fit = a.value("fit") ? split_list(*a.value("fit")) : std::vector<std::string>{};
  if (problem.fit.empty()) {  // every positive number given
    for (const auto& [key, value] : start.items())
      if (value.is_number() && value.get<double>() > 0.0) problem.fit.push_back(key);
  }
  const double f_min = a.number("fmin", 1.0), f_max = a.number("fmax", 100.0);
  if (!(f_min > 0.0) || !(f_max > f_min) || !std::isfinite(f_max))
    throw UsageError("need 0 < --fmin < --fmax (finite frequencies in Hz)");
  const auto frequency =
      log_frequencies(f_min, f_max, static_cast<int>(a.integer("points", 40, 2, 100000)));
  if (!soil_frf(*target.soil, problem.layout.size(), frequency,
                static_cast<std::size_t>(a.integer("terms", 2, 0, 1000)), problem.target)) {
    throw ConfigError("target soil '" + target.soil->type_name() +
                      "' offers no frequency response");
  }
  const CalibrationResult result = calibrate(problem);
  nlohmann::json report = {{"model", model_name},
                           {"target", doc->path.string()},
                           {"band_hz", {frequency.front(), frequency.back()}},
                           {"fitted", problem.fit},
                           {"params", result.params},
                           {"relative_rms_residual", result.relative_rms},
                           {"iterations", result.iterations},
                           {"converged", result.converged}};
  std::cout << report.dump(2) << '\n';
  if (const auto out = a.value("output")) {  // a new file: never written through a link
    const std::filesystem::path file(*out);
    replace_file(file, file.string() + ".tmp", report.dump(2) + '\n');
  }
  return kExitOk;
}

}  // namespace rumble::cli
