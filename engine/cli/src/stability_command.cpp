// `rumble stability FILE [--macro-steps 1e-3,5e-4,...] [--extrapolation P] [--interpolation Q]
// [--output FILE]`: the spectral radius of one macro step of gauss_seidel and jacobi for the
// scenario's track on its soil, linearized at rest (analysis/coupling_stability.hpp), per macro
// step: a table, and JSON with --output. The input orders are the scenario's coupling params
// (gauss_seidel, jacobi; 0 for another coupler) unless the options give them.
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "analysis/coupling_stability.hpp"
#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "cli/scenario_prepare.hpp"
#include "core/errors.hpp"
#include "parallel/mpi_session.hpp"
#include "results/new_file.hpp"

namespace rumble::cli {
namespace {

/// Whether `file` holds what an earlier `rumble stability --output` wrote: a JSON array of
/// points with a "spectral_radius".
bool holds_stability_points(const std::filesystem::path& file) {
  std::ifstream in(file);
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    return j.is_array() && !j.empty() && j.front().is_object() &&
           j.front().contains("spectral_radius");
  } catch (const std::exception&) {
    return false;
  }
}

/// --output FILE is written only where nothing stands, or over what an earlier `rumble
/// stability` wrote there, and never through a link (a command line writes nothing it did not
/// create: docs/scenario.md, "The results directory"). Checked before the analysis runs.
void check_output(const std::filesystem::path& file) {
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::symlink_status(file, ec);
  if (!std::filesystem::exists(st)) return;
  const std::string why = std::filesystem::is_symlink(st)         ? "is a symbolic link"
                          : !std::filesystem::is_regular_file(st) ? "is not a regular file"
                          : !holds_stability_points(file)
                              ? "holds something other than an earlier rumble stability result"
                              : "";
  if (!why.empty())
    throw UsageError("--output " + file.string() + ": " + why +
                     "; rumble stability replaces only a file it wrote: name a new file");
}

}  // namespace

int stability_command(const std::vector<std::string>& args) {
  const Arguments a(args, {}, {"macro-steps", "output", "extrapolation", "interpolation"});
  if (a.positional().size() != 1) {
    throw UsageError(
        "usage: rumble stability FILE [--macro-steps 1e-3,5e-4,2e-4,1e-4] [--extrapolation 0..2] "
        "[--interpolation 0..1] [--output FILE.json]");
  }
  std::vector<double> steps;
  for (const std::string& item :
       split_list(a.value("macro-steps").value_or("1e-3,5e-4,2e-4,1e-4"))) {
    std::size_t used = 0;
    double H = 0.0;
    try {
      H = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || !(H > 0.0) || !std::isfinite(H)) {
      throw UsageError("--macro-steps: '" + item + "' is not a positive number of seconds");
    }
    steps.push_back(H);
  }
  if (const auto file = a.value("output")) check_output(*file);
  PluginRegistry registry;
  BuiltSoils built;  // the soil validation builds is the one analysed: built once
  scenario::CheckOptions check = kNotARun;
  check.keep_soils = &built;
  check.ranks = parallel::world_size();  // a distributed soil split so has no whole matrices
  check.whole_soil = {"rumble stability", "it linearizes the track on the soil", "linear_matrix"};
  const auto doc =
      prepare_scenario(a.positional()[0], registry, scenario::Format::kText, {}, check);
  if (!doc) return kExitConfig;
  // The scenario's explicit scheme feeds its inputs so; the options override.
  const nlohmann::json& coupling = doc->json.at("coupling");
  const std::string type = coupling.at("type").get<std::string>();
  const nlohmann::json& params = coupling.at("params");  // validated, the coupler's defaults in
  StabilityInputs inputs;
  if (type == "gauss_seidel" || type == "jacobi")
    inputs.extrapolation = params.at("extrapolation").get<std::uint32_t>();
  if (type == "gauss_seidel")
    inputs.interpolation = params.at("interpolation").get<std::uint32_t>();
  inputs.extrapolation = static_cast<std::uint32_t>(
      a.integer("extrapolation", static_cast<long long>(inputs.extrapolation), 0, 2));
  inputs.interpolation = static_cast<std::uint32_t>(
      a.integer("interpolation", static_cast<long long>(inputs.interpolation), 0, 1));
  const auto points = coupling_stability(scenario::make_run_spec(doc->json, doc->path), registry,
                                         steps, inputs, &built);
  std::cout << "spectral radius of one macro step, linearized at rest (> 1: grows by that factor "
               "every step, the run diverges); inputs extrapolated to order "
            << inputs.extrapolation << ", gauss_seidel's interpolated to order "
            << inputs.interpolation << "\n"
            << "  H [s]        gauss_seidel  jacobi\n";
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t k = 0; k + 1 < points.size(); k += 2) {
    std::cout << "  " << std::setw(11) << std::left << points[k].macro_step << "  " << std::setw(12)
              << points[k].spectral_radius << "  " << points[k + 1].spectral_radius << '\n';
  }
  for (const StabilityPoint& p : points) {
    out.push_back({{"scheme", p.scheme},
                   {"macro_step_s", p.macro_step},
                   {"extrapolation", inputs.extrapolation},
                   {"interpolation", p.scheme == "gauss_seidel" ? inputs.interpolation : 0u},
                   {"spectral_radius", p.spectral_radius},
                   {"state_size", p.state_size}});
  }
  if (const auto file = a.value("output")) {
    replace_file(*file, *file + ".tmp", out.dump(2) + '\n');
    std::cout << "wrote " << *file << '\n';
  }
  return kExitOk;
}

}  // namespace rumble::cli
