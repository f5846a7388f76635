// Measuring a run's receivers: the indicators of each velocity component and of each receiver,
// raw and within the band the soil resolves. Numbers only, so that what is measured reads apart
// from how it is written (docs/post-processing.md describes every indicator).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "core/number_text.hpp"
#include "post/din4150.hpp"
#include "post/peak_frequency.hpp"
#include "post/resolved_band.hpp"
#include "post_run_steps.hpp"

namespace rumble::post::detail {
namespace {

GuideCheck nan_check() {
  return {kNaN, kNaN};
}

/// KB_F,max, the dominant frequency and the guide ratios of the record low-passed at the
/// resolved frequency (`low`, one per component, as rr.components), as the raw ones are found:
/// the governing component is the one with the largest low-passed peak, its dominant frequency
/// the zero crossings of that peak's half cycle (none: no guide ratio).
void measure_band_indicators(ReceiverResult& rr, const std::vector<std::vector<double>>& low,
                             double dt) {
  rr.kb_f_max_resolved = 0.0;
  std::size_t governing = 0;
  Peak governing_peak;
  for (std::size_t i = 0; i < low.size(); ++i) {
    rr.kb_f_max_resolved =
        std::max(rr.kb_f_max_resolved, kb_f(TimeSeries{0.0, dt, low[i]}).kb_f_max);
    const Peak p = peak_abs(low[i]);
    if (i == 0 || p.value > governing_peak.value) {
      governing = i;
      governing_peak = p;
    }
  }
  const double f = peak_half_cycle_frequency(low[governing], governing_peak.index, dt);
  if (!(f > 0.0) || !std::isfinite(f)) return;
  rr.dominant_f_resolved = f;
  for (int l = 0; l < 3; ++l)
    rr.din_resolved[l] = check_din4150_3(kDinLines[l], governing_peak.value, f);
  for (int l = 0; l < 2; ++l)
    rr.bs_resolved[l] = check_bs7385_2(kBsLines[l], governing_peak.value, f);
}

/// What an unresolved share of energy means for rr's PPV: the raw PPV is the mesh's when less
/// than kResolvedPpvShare of it is left within the band; else only what lies above f is (its
/// spectrum, band levels and scalogram there), and the PPV holds.
std::string ppv_verdict(const ReceiverResult& rr, double f) {
  const std::string raw = number_text(rr.ppv_z, 3), band = number_text(rr.ppv_z_resolved, 3);
  if (!(rr.ppv_z_resolved >= kResolvedPpvShare * rr.ppv_z))
    return "its raw PPV (" + raw + " m/s) is mostly the mesh's; within the band " + band +
           " m/s (ppv.csv, \"resolved\" columns)";
  const std::string kept = number_text(rr.ppv_z_resolved / rr.ppv_z, 2);
  return "its PPV within the band, " + band + " m/s, is " + kept + " of the raw one (" + raw +
         " m/s; ppv.csv, \"resolved\" columns), but what it records above " + number_text(f, 3) +
         " Hz (spectrum, band levels, scalogram) is the mesh's";
}

/// The share of rr's vertical energy above its resolved frequency and its indicators below it;
/// a warning when the share passes kUnresolvedShare.
void measure_resolved_band(ReceiverResult& rr, double dt, SpectrumAnalyzer& rect,
                           std::vector<std::string>& warnings) {
  const double f = rr.rx->resolved_f;
  if (!(f > 0.0)) return;
  const ComponentResult& z = rr.vz();
  rr.energy_above_resolved = energy_share_above(rect.power(z.v.values, dt), f);
  std::vector<std::vector<double>> low;
  for (const ComponentResult& c : rr.components)
    low.push_back(zero_phase_low_pass(c.v.values, dt, f));
  rr.ppv_z_resolved = peak_abs(low.back()).value;
  if (low.size() == 3) rr.ppv_3c_resolved = peak_vector(low[0], low[1], low[2]).value;
  measure_band_indicators(rr, low, dt);
  if (rr.energy_above_resolved > kUnresolvedShare)
    warnings.push_back("receiver '" + rr.rx->name +
                       "': " + number_text(100.0 * rr.energy_above_resolved, 3) +
                       " % of its vertical velocity's energy lies above " + number_text(f, 3) +
                       " Hz, the band its soil's mesh resolves there: " + ppv_verdict(rr, f) +
                       ". Refine the mesh along the path (mesh.f_max, mesh.near_distance) for "
                       "the whole record");
}

/// One velocity component on the grid with its indicators: peak, amplitude spectrum, dominant
/// frequency, KB_F,max, v_eff,max, rms and band levels.
ComponentResult measure_component(const char* component, const std::vector<double>& time,
                                  const std::vector<double>& values, Measuring& m) {
  const double dt = m.grid.dt;
  ComponentResult cr;
  cr.component = component;
  cr.v = on_grid(time, values, m.grid);
  cr.peak = peak_abs(cr.v.values);
  cr.amplitude = m.hann.amplitude(cr.v.values, dt);
  // The peak's half cycle (event-bound); a peak whose half cycle never closes in the record
  // falls back to the spectrum's largest amplitude.
  // The frequency of a half cycle lasting 1e308 s is 0 Hz (underflow), where no guide value
  // is defined (std::invalid_argument escaped; found by the post fuzz target): the spectrum's.
  cr.dominant_f = peak_half_cycle_frequency(cr.v.values, cr.peak.index, dt);
  if (!(cr.dominant_f > 0.0) || !std::isfinite(cr.dominant_f))
    cr.dominant_f = dominant_frequency(cr.amplitude, m.options.dominant_f_min);
  const KbResult kb = kb_f(cr.v);
  cr.kb_f_max = kb.kb_f_max;
  cr.t_kb_f_max = kb.t_max;
  cr.v_eff_max = effective_velocity_max(cr.v);
  cr.v_rms = effective_value(cr.v.values);
  cr.bands = band_levels(m.rect.power(cr.v.values, dt), m.bands, m.options.velocity_reference);
  return cr;
}

/// The receiver's indicators over its components: the vertical and vector peaks, the governing
/// component (the largest peak), the largest KB_F,max and v_eff,max, and the guide values at the
/// governing component's dominant frequency.
void combine_components(ReceiverResult& rr) {
  const ComponentResult& z = rr.vz();
  rr.ppv_z = z.peak.value;
  rr.t_ppv_z = z.v.time(z.peak.index);
  if (rr.rx->three_component()) {
    const Peak p = peak_vector(rr.components[0].v.values, rr.components[1].v.values,
                               rr.components[2].v.values);
    rr.ppv_3c = p.value;
    rr.t_ppv_3c = z.v.time(p.index);
  }
  for (std::size_t i = 0; i < rr.components.size(); ++i) {
    if (rr.components[i].peak.value > rr.components[rr.governing].peak.value) rr.governing = i;
    rr.kb_f_max = std::max(rr.kb_f_max, rr.components[i].kb_f_max);
    rr.v_eff_max = std::max(rr.v_eff_max, rr.components[i].v_eff_max);
  }
  const ComponentResult& g = rr.components[rr.governing];
  for (int l = 0; l < 3; ++l)
    rr.din[l] = std::isfinite(g.dominant_f)
                    ? check_din4150_3(kDinLines[l], g.peak.value, g.dominant_f)
                    : nan_check();
  for (int l = 0; l < 2; ++l)
    rr.bs[l] = std::isfinite(g.dominant_f) ? check_bs7385_2(kBsLines[l], g.peak.value, g.dominant_f)
                                           : nan_check();
}

ReceiverResult measure_receiver(const Receiver& rx, const CsvTable& table, Measuring& m,
                                std::vector<std::string>& warnings) {
  ReceiverResult rr;
  rr.rx = &rx;
  for (int c = 0; c < 3; ++c)
    if (rx.column[c])
      rr.components.push_back(
          measure_component(kComponents[c], table.time, table.columns[*rx.column[c]], m));
  combine_components(rr);
  measure_resolved_band(rr, m.grid.dt, m.rect, warnings);
  if (!std::isfinite(rr.components[rr.governing].dominant_f))
    warnings.push_back("receiver '" + rx.name + "': no spectral content above " +
                       number_text(m.options.dominant_f_min, 9) +
                       " Hz, so no dominant frequency and no guide values");
  return rr;
}

}  // namespace

UniformGrid record_grid(const CsvTable& table, const fs::path& results_dir,
                        const PostOptions& options, std::vector<std::string>& warnings) {
  const UniformGrid grid =
      uniform_grid(table.time, "receivers.csv in " + quoted(results_dir), options.max_step_ratio);
  if (grid.resampled)
    warnings.push_back(
        "receivers.csv: the time step varies; the record was linearly "
        "interpolated onto a uniform step of " +
        number_text(grid.dt, 9) + " s (the median step)");
  return grid;
}

void check_velocity_reference(const PostOptions& options) {
  if (!(options.velocity_reference > 0.0))
    throw std::runtime_error("post-processing option velocity_reference = " +
                             number_text(options.velocity_reference, 9) +
                             " m/s is not > 0; use 1e-9 (ISO 1683) or 2.54e-8 (VdB)");
}

std::vector<ReceiverResult> measure_receivers(const RunRecord& run, Measuring& m,
                                              std::vector<std::string>& warnings) {
  std::vector<ReceiverResult> results;
  for (const Receiver& rx : run.receivers)
    results.push_back(measure_receiver(rx, run.table, m, warnings));
  std::stable_sort(results.begin(), results.end(),
                   [](const ReceiverResult& a, const ReceiverResult& b) {
                     return std::tie(a.rx->distance, a.rx->depth, a.rx->name) <
                            std::tie(b.rx->distance, b.rx->depth, b.rx->name);
                   });
  return results;
}

}  // namespace rumble::post::detail
