// The outline of post-processing, kept short so that it reads as the algorithm: read the run,
// measure every receiver, choose the scalograms, write post/; with the options a run's scenario
// asked for. Each step lives in a file of its own (post_run_steps.hpp names them).
#include "post/post_run.hpp"

#include <exception>
#include <utility>
#include <vector>

#include "core/input_file.hpp"
#include "post_run_steps.hpp"

namespace rumble::post {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

}  // namespace

PostOptions options_from_scenario(const nlohmann::json& scenario, PostOptions base) {
  const auto outputs = scenario.find("outputs");
  if (outputs == scenario.end() || !outputs->contains("post")) return base;
  const nlohmann::json& post = outputs->at("post");
  if (const auto d = post.find("cwt_distances"); d != post.end())
    base.cwt_distances = d->get<std::vector<double>>();
  if (const auto f = post.find("f_max"); f != post.end()) base.cwt_f_max = f->get<double>();
  if (const auto r = post.find("reference"); r != post.end())
    base.velocity_reference = *r == "vdb" ? kVelocityRefVdb : kVelocityRefIso1683;
  return base;
}

PostOptions options_from_summary(const fs::path& results_dir) {
  const fs::path file = results_dir / "summary.json";
  if (!input_file_problem(file, kMaxResultJsonBytes).empty()) return {};
  try {
    const json summary = json::parse(read_input_file(file, kMaxResultJsonBytes));
    if (const auto s = summary.find("scenario"); s != summary.end() && s->is_object())
      return options_from_scenario(*s);
  } catch (const std::exception&) {  // a damaged summary: the defaults
  }
  return {};
}

PostResult post_process(const fs::path& results_dir, const PostOptions& options) {
  using namespace detail;
  PostResult result;
  RunRecord run = read_run(results_dir);
  result.warnings = run.table.warnings;
  cut_at_divergence(run, result.warnings, results_dir);
  const UniformGrid grid = record_grid(run.table, results_dir, options, result.warnings);
  check_velocity_reference(options);

  Measuring measuring(grid, options);
  const std::vector<ReceiverResult> results = measure_receivers(run, measuring, result.warnings);
  std::vector<std::size_t> cwt_of = choose_cwt_receivers(results, options, results_dir);
  const CwtOptions cwt_options = cwt_options_for(options, grid, cwt_of, result.warnings);

  result.directory = results_dir / "post";
  make_directory(result.directory);
  write_ppv_csv(results, result);
  write_spectra_csv(results, options.spectrum_f_max, result);
  write_third_octave_csv(results, measuring.bands, options.velocity_reference, result);
  json cwt_json = write_scalograms(results, cwt_of, grid, cwt_options, result);
  write_post_json(results_dir, options, Findings{run, grid, measuring.bands, results, cwt_options},
                  std::move(cwt_json), result);
  return result;
}

}  // namespace rumble::post
