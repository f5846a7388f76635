// Writing post.json: the numbers of the CSV files with the options, the sampling, the warnings
// and the files written. Apart from the CSV files because its keys are an interface of their
// own, which scripts and reports parse (docs/post-processing.md).
#include <string>
#include <utility>
#include <vector>

#include "post/din4150.hpp"
#include "post_run_steps.hpp"

namespace rumble::post::detail {
namespace {

json options_json(const PostOptions& options, const CwtOptions& cwt_options) {
  return {{"cwt_receivers", options.cwt_receivers},
          {"cwt_distances_m", options.cwt_distances},
          {"cwt_f_min_hz", cwt_options.f_min},
          {"cwt_f_max_hz", cwt_options.f_max},
          {"cwt_n_freq", cwt_options.n_freq},
          {"cwt_omega0", cwt_options.omega0},
          {"cwt_time_stride", cwt_options.time_stride},
          {"velocity_reference_m_s", options.velocity_reference},
          {"spectrum_window", "hann"},
          {"third_octave_window", "rectangular"},
          {"dominant_f_min_hz", options.dominant_f_min},
          {"kb_tau_s", kFastTau},
          {"kb_corner_hz", kKbCornerHz}};
}

/// post.json's "components" of a receiver: each component's indicators and band levels.
json components_json(const ReceiverResult& rr) {
  json components = json::object();
  for (const ComponentResult& c : rr.components) {
    json levels = json::array();
    for (const BandLevel& b : c.bands)
      levels.push_back(
          {{"band_hz", b.band.nominal}, {"rms_m_s", b.rms}, {"level_db", number_or_null(b.level)}});
    components[c.component] = {{"ppv_m_s", number_or_null(c.peak.value)},
                               {"t_ppv_s", c.v.time(c.peak.index)},
                               {"dominant_frequency_hz", number_or_null(c.dominant_f)},
                               {"kb_f_max_m_s", number_or_null(c.kb_f_max)},
                               {"t_kb_f_max_s", c.t_kb_f_max},
                               {"v_eff_f_max_m_s", number_or_null(c.v_eff_max)},
                               {"v_rms_m_s", number_or_null(c.v_rms)},
                               {"third_octave", levels}};
  }
  return components;
}

/// post.json's "resolved_band" of a receiver.
json resolved_band_json(const ReceiverResult& rr) {
  return {{"f_hz", number_or_null(rr.rx->resolved_f)},
          {"energy_z_above", number_or_null(rr.energy_above_resolved)},
          {"ppv_z_m_s", number_or_null(rr.ppv_z_resolved)},
          {"ppv_3c_m_s", number_or_null(rr.ppv_3c_resolved)},
          {"kb_f_max_m_s", number_or_null(rr.kb_f_max_resolved)},
          {"dominant_frequency_hz", number_or_null(rr.dominant_f_resolved)},
          {"din4150_3_ratios",
           {number_or_null(rr.din_resolved[0].ratio), number_or_null(rr.din_resolved[1].ratio),
            number_or_null(rr.din_resolved[2].ratio)}},
          {"bs7385_2_ratios",
           {number_or_null(rr.bs_resolved[0].ratio), number_or_null(rr.bs_resolved[1].ratio)}},
          {"low_pass", "zero-phase Butterworth order 4 (-3 dB at f_hz)"},
          {"warning_share", kUnresolvedShare}};
}

/// post.json's entry of a receiver.
json receiver_json(const ReceiverResult& rr) {
  const ComponentResult& g = rr.components[rr.governing];
  json din = json::array(), bs = json::array();
  for (int l = 0; l < 3; ++l)
    din.push_back({{"line", l + 1},
                   {"guide_m_s", number_or_null(rr.din[l].guide)},
                   {"ratio", number_or_null(rr.din[l].ratio)}});
  for (int l = 0; l < 2; ++l)
    bs.push_back({{"line", l + 1},
                  {"guide_m_s", number_or_null(rr.bs[l].guide)},
                  {"ratio", number_or_null(rr.bs[l].ratio)}});
  return {{"name", rr.rx->name},
          {"x_m", number_or_null(rr.rx->x)},
          {"distance_m", rr.rx->distance},
          {"depth_m", rr.rx->depth},
          {"ppv_z_m_s", number_or_null(rr.ppv_z)},
          {"t_ppv_z_s", rr.t_ppv_z},
          {"ppv_3c_m_s", number_or_null(rr.ppv_3c)},
          {"t_ppv_3c_s", number_or_null(rr.t_ppv_3c)},
          {"resolved_band", resolved_band_json(rr)},
          {"governing_component", g.component},
          {"ppv_max_component_m_s", number_or_null(g.peak.value)},
          {"dominant_frequency_hz", number_or_null(g.dominant_f)},
          {"kb_f_max_m_s", number_or_null(rr.kb_f_max)},
          {"v_eff_f_max_m_s", number_or_null(rr.v_eff_max)},
          {"din4150_3", din},
          {"bs7385_2", bs},
          {"components", components_json(rr)}};
}

}  // namespace

void write_post_json(const fs::path& results_dir, const PostOptions& options, const Findings& f,
                     json cwt_json, PostResult& result) {
  json& report = result.report;
  report["results_directory"] = results_dir.string();
  report["source"] = {{"file", "receivers.csv"}, {"form", f.run.form}};
  const std::size_t n = f.grid.count;
  report["sampling"] = {{"t0_s", f.grid.t0},
                        {"dt_s", f.grid.dt},
                        {"samples", n},
                        {"duration_s", static_cast<double>(n) * f.grid.dt},
                        {"resampled", f.grid.resampled}};
  report["options"] = options_json(options, f.cwt_options);
  json receivers = json::array();
  for (const ReceiverResult& rr : f.receivers) receivers.push_back(receiver_json(rr));
  report["receivers"] = receivers;
  json bands_json = json::array();
  for (const ThirdOctaveBand& b : f.bands)
    bands_json.push_back({{"band_hz", b.nominal},
                          {"f_m_hz", b.centre},
                          {"f_lower_hz", b.lower},
                          {"f_upper_hz", b.upper}});
  report["third_octave_bands"] = bands_json;
  report["cwt"] = std::move(cwt_json);
  report["warnings"] = result.warnings;
  json files = json::array();
  for (const fs::path& file : result.files) files.push_back(file.filename().string());
  files.push_back("post.json");
  report["files"] = files;
  const fs::path path = result.directory / "post.json";
  write_whole(path, report.dump(2) + "\n");
  result.files.push_back(path);
}

}  // namespace rumble::post::detail
