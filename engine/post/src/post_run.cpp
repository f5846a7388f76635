#include "post/post_run.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <tuple>

#include "core/input_file.hpp"
#include "core/number_text.hpp"
#include "post/cwt.hpp"
#include "post/din4150.hpp"
#include "post/guide_values.hpp"
#include "post/peak_frequency.hpp"
#include "post/ppv.hpp"
#include "post/resolved_band.hpp"
#include "post/spectrum.hpp"
#include "post/time_series.hpp"
#include "results/new_file.hpp"

namespace rumble::post {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// A receiver with more than this share of its vertical energy above its resolved band is warned
// about (docs/post-processing.md, "The resolved band"): its raw indicators are then mostly the
// mesh's.
constexpr double kUnresolvedShare = 0.2;
constexpr const char* kComponents[3] = {"vx", "vy", "vz"};

// JSON has no NaN or infinity: null stands for "not available".
json number_or_null(double v) {
  return std::isfinite(v) ? json(v) : json(nullptr);
}

std::string quoted(const fs::path& p) {
  return "'" + p.string() + "'";
}

// ---------------------------------------------------------------------------------------------
// Reading the run

struct Receiver {
  std::string name;
  double x = kNaN, distance = kNaN, depth = 0.0;  // m
  double resolved_f = kNaN;  // Hz, the band the soil carries here (summary.json; NaN: unknown)
  // Column index in the CSV table per component vx, vy, vz; vertical-only receivers have vz.
  std::optional<std::size_t> column[3];
  bool three_component() const { return column[0] && column[1] && column[2]; }
};

// "d=2.500000 m [m/s]" -> 2.5 (the older surface receivers' column); nullopt for other names,
// and for a distance that is not finite ("d=-inf m [m/s]": no receiver the engine places, and
// its rows, sorted by distance, went out as -inf; found by the post fuzz target).
std::optional<double> distance_column(const std::string& name) {
  const std::string head = "d=", tail = " m [m/s]";
  if (name.size() <= head.size() + tail.size() || name.compare(0, head.size(), head) != 0 ||
      name.compare(name.size() - tail.size(), tail.size(), tail) != 0)
    return std::nullopt;
  const char* first = name.data() + head.size();
  const char* last = name.data() + name.size() - tail.size();
  double d = 0.0;
  const auto [ptr, ec] = std::from_chars(first, last, d);
  if (ec != std::errc() || ptr != last || !std::isfinite(d)) return std::nullopt;
  return d;
}

// "d=2.5 m" -> 2.5 (the name the engine gives a distance receiver, run_spec.cpp).
std::optional<double> distance_name(const std::string& name) {
  return distance_column(name + " [m/s]");
}

std::string distance_label(double d) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "d=%g m", d);  // as engine/scenario/src/run_spec.cpp
  return buf;
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

std::string list_names(const std::vector<std::string>& names, std::size_t max = 8) {
  std::string out;
  for (std::size_t i = 0; i < names.size() && i < max; ++i)
    out += (i ? ", '" : "'") + names[i] + "'";
  if (names.size() > max) out += ", ... (" + std::to_string(names.size()) + " in all)";
  return out.empty() ? "none" : out;
}

std::optional<json> read_summary(const fs::path& dir) {
  const fs::path file = dir / "summary.json";
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(file, ec))) return std::nullopt;
  if (const std::string problem = input_file_problem(file, kMaxResultJsonBytes); !problem.empty())
    throw std::runtime_error("summary.json in " + quoted(dir) + " " + problem +
                             ": rumble post reads the summary.json a run wrote, a regular file "
                             "of at most 64 MiB; rerun the scenario into the directory");
  const std::string text = read_input_file(file, kMaxResultJsonBytes);
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    throw std::runtime_error("summary.json in " + quoted(dir) + " is not valid JSON (" + e.what() +
                             "); the run was cut while writing it. Rerun the scenario");
  }
}

// Positions from summary.json's "ppv" entries: by name (probes) or in column order (distances).
void place_receivers(std::vector<Receiver>& receivers, bool probes, const fs::path& dir) {
  const std::optional<json> summary = read_summary(dir);
  const json* ppv = nullptr;
  if (summary && summary->contains("ppv") && (*summary)["ppv"].is_array()) ppv = &(*summary)["ppv"];
  auto get = [](const json& e, const char* key, double fallback) {
    return e.contains(key) && e[key].is_number() ? e[key].get<double>() : fallback;
  };
  for (std::size_t r = 0; r < receivers.size(); ++r) {
    Receiver& rx = receivers[r];
    const json* entry = nullptr;
    if (ppv && probes) {
      for (const json& e : *ppv)
        if (e.contains("name") && e["name"].is_string() && e["name"] == rx.name) entry = &e;
    } else if (ppv && r < ppv->size()) {
      entry = &(*ppv)[r];
    }
    if (entry) {
      rx.distance = get(*entry, "distance_m", rx.distance);
      rx.x = get(*entry, "x_m", rx.x);
      rx.depth = get(*entry, "depth_m", rx.depth);
      rx.resolved_f = get(*entry, "resolved_f_hz", kNaN);
    }
    if (std::isnan(rx.distance)) {
      if (const auto d = distance_name(rx.name)) rx.distance = *d;
    }
    if (std::isnan(rx.distance)) {
      throw std::runtime_error(
          (summary ? "summary.json in " + quoted(dir) + " has no \"ppv\" entry with \"name\": \"" +
                         rx.name + "\" and \"distance_m\""
                   : "summary.json is missing in " + quoted(dir)) +
          ", so the distance of receiver '" + rx.name +
          "' from the track is unknown. Post-process a complete results directory (rerun the "
          "scenario if summary.json was lost)");
    }
  }
}

struct RunRecord {
  CsvTable table;
  std::vector<Receiver> receivers;
  std::string form;  // "probes" or "distances"
};

RunRecord read_run(const fs::path& dir) {
  if (!fs::is_directory(dir))
    throw std::runtime_error("results directory " + quoted(dir) +
                             " does not exist or is not a directory; give the outputs.directory "
                             "of a run (e.g. scenarios/paper/results/...)");
  const fs::path file = dir / "receivers.csv";
  if (!fs::exists(file))
    throw std::runtime_error("no receivers.csv in " + quoted(dir) +
                             ": the run recorded no receivers. Add receivers to the scenario "
                             "(outputs.receivers, docs/scenario.md) and rerun it");
  RunRecord run;
  run.table = read_csv(file);
  const CsvTable& t = run.table;
  const std::string where = "receivers.csv in " + quoted(dir);
  // Probe receivers: "<name> vz [m/s]" with its vx and vy siblings.
  for (const std::string& col : t.names) {
    if (!ends_with(col, " vz [m/s]")) continue;
    Receiver rx;
    rx.name = col.substr(0, col.size() - std::string(" vz [m/s]").size());
    for (int c = 0; c < 3; ++c) {
      const std::string want = rx.name + " " + kComponents[c] + " [m/s]";
      rx.column[c] = t.find(want);
      if (!rx.column[c])
        throw std::runtime_error(where + " has no column '" + want + "' (it has '" + col +
                                 "'); the file is incomplete or was edited. Rerun the scenario "
                                 "(outputs.receivers lists the receivers)");
    }
    run.receivers.push_back(rx);
  }
  if (!run.receivers.empty()) {
    run.form = "probes";
  } else {
    for (std::size_t c = 0; c < t.names.size(); ++c) {
      if (const auto d = distance_column(t.names[c])) {
        Receiver rx;
        rx.name = distance_label(*d);
        rx.distance = *d;
        rx.column[2] = c;
        run.receivers.push_back(rx);
      }
    }
    run.form = "distances";
  }
  if (run.receivers.empty())
    throw std::runtime_error(where +
                             " has no receiver velocity column: expected '<name> vz [m/s]' "
                             "or 'd=<distance> m [m/s]', found " +
                             list_names(t.names) +
                             ". Rerun with receivers in the scenario (outputs.receivers)");
  place_receivers(run.receivers, run.form == "probes", dir);
  return run;
}

// The run's status as its summary.json gives it ("" when it does not say).
std::string run_status(const fs::path& dir) {
  const std::optional<json> summary = read_summary(dir);
  return summary && summary->contains("status") && (*summary)["status"].is_string()
             ? (*summary)["status"].get<std::string>()
             : "";
}

// Cuts the record before the first non-finite velocity (a diverged run) and says so. A run that
// completed writes finite numbers only: then the file is blamed, not the run.
void cut_at_divergence(RunRecord& run, std::vector<std::string>& warnings, const fs::path& dir) {
  CsvTable& t = run.table;
  std::size_t first_bad = t.time.size();
  std::string column;
  for (const Receiver& rx : run.receivers)
    for (const auto& c : rx.column) {
      if (!c) continue;
      const std::vector<double>& v = t.columns[*c];
      for (std::size_t i = 0; i < first_bad; ++i)
        if (!std::isfinite(v[i])) {
          first_bad = i;
          column = t.names[*c];
          break;
        }
    }
  if (first_bad == t.time.size()) return;
  if (const std::string status = run_status(dir); status == "completed")
    throw std::runtime_error(
        "receivers.csv in " + quoted(dir) + ": column '" + column + "' is not finite at t = " +
        number_text(t.time[first_bad], 9) + " s (data row " + std::to_string(first_bad + 1) +
        "), but summary.json says the run completed, which writes finite numbers only: the "
        "file was damaged or edited after the run. Rerun the scenario");
  if (first_bad < 2)
    throw std::runtime_error(
        "receivers.csv in " + quoted(dir) + ": column '" + column +
        "' is not finite from its first rows (t = " + number_text(t.time[first_bad], 9) +
        " s); the run diverged at once. Check the run's summary.json "
        "status and stability, then rerun with a smaller macro step");
  warnings.push_back("receivers.csv: '" + column +
                     "' is not finite from t = " + number_text(t.time[first_bad], 9) +
                     " s (the run diverged); the indicators use the " + std::to_string(first_bad) +
                     " rows before it");
  t.time.resize(first_bad);
  for (std::vector<double>& v : t.columns) v.resize(first_bad);
}

// ---------------------------------------------------------------------------------------------
// Computing

struct ComponentResult {
  std::string component;  // vx, vy, vz
  TimeSeries v;
  Peak peak;
  double dominant_f = kNaN;                                               // Hz
  double kb_f_max = 0.0, t_kb_f_max = 0.0, v_eff_max = 0.0, v_rms = 0.0;  // m/s, s
  Spectrum amplitude;
  std::vector<BandLevel> bands;
};

constexpr Din4150Line kDinLines[3] = {Din4150Line::kCommercial, Din4150Line::kDwelling,
                                      Din4150Line::kSensitive};
constexpr Bs7385Line kBsLines[2] = {Bs7385Line::kReinforced, Bs7385Line::kUnreinforced};

struct ReceiverResult {
  const Receiver* rx = nullptr;
  std::vector<ComponentResult> components;  // vx vy vz, or vz alone
  double ppv_z = 0.0, t_ppv_z = 0.0, ppv_3c = kNaN, t_ppv_3c = kNaN;
  std::size_t governing = 0;               // index in components of the largest component peak
  double kb_f_max = 0.0, v_eff_max = 0.0;  // m/s, largest over components
  GuideCheck din[3], bs[2];
  // Within the resolved band (NaN when the soil did not say): the share of v_z's energy above
  // it [-], and the peaks of the record low-passed at it [m/s] (post/resolved_band.hpp).
  double energy_above_resolved = kNaN, ppv_z_resolved = kNaN, ppv_3c_resolved = kNaN;
  // The other indicators of the low-passed record: KB_F,max over the components [m/s], the
  // governing component's dominant frequency [Hz] and the guide values' ratios at it.
  double kb_f_max_resolved = kNaN, dominant_f_resolved = kNaN;
  GuideCheck din_resolved[3] = {{kNaN, kNaN}, {kNaN, kNaN}, {kNaN, kNaN}};
  GuideCheck bs_resolved[2] = {{kNaN, kNaN}, {kNaN, kNaN}};

  const ComponentResult& vz() const { return components.back(); }
};

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
    warnings.push_back(
        "receiver '" + rr.rx->name + "': " + number_text(100.0 * rr.energy_above_resolved, 3) +
        " % of its vertical velocity's energy lies above " + number_text(f, 3) +
        " Hz, the band its soil's mesh resolves there: its raw PPV (" + number_text(rr.ppv_z, 3) +
        " m/s) is mostly the mesh's; within the band " + number_text(rr.ppv_z_resolved, 3) +
        " m/s (ppv.csv, \"resolved\" columns). Refine the mesh along the path "
        "(mesh.f_max, mesh.near_distance) for the whole record");
}

// For each wanted distance, the nearest receiver not yet chosen (surface before depth).
std::vector<std::size_t> default_cwt_receivers(const std::vector<Receiver>& receivers,
                                               const std::vector<double>& distances) {
  std::vector<std::size_t> chosen;
  for (double target : distances) {
    std::optional<std::size_t> best;
    for (std::size_t r = 0; r < receivers.size(); ++r) {
      if (std::find(chosen.begin(), chosen.end(), r) != chosen.end()) continue;
      auto key = [&](std::size_t i) {
        return std::make_pair(std::abs(receivers[i].distance - target), receivers[i].depth);
      };
      if (!best || key(r) < key(*best)) best = r;
    }
    if (best) chosen.push_back(*best);
  }
  return chosen;
}

std::string file_name_for(const std::string& receiver) {
  std::string out;
  for (char c : receiver) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '.' || c == '-' || c == '_' || c == '=';
    out += keep ? c : '_';
  }
  return "cwt_" + out + ".csv";
}

// ---------------------------------------------------------------------------------------------
// Writing

/// Writes `text` as the new file `path` (through path + ".tmp"); throws naming the file.
void write_whole(const fs::path& path, const std::string& text) {
  replace_file(path, fs::path(path.string() + ".tmp"), text);
}

/// The directory `path`, created when missing; a file or link standing at its name is replaced,
/// never followed.
void make_directory(const fs::path& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) return;
  if ((::unlink(path.c_str()) != 0 && errno != ENOENT) || ::mkdir(path.c_str(), 0777) != 0) {
    const int err = errno;
    throw std::runtime_error("cannot create " + quoted(path) + ": " + std::strerror(err) +
                             "; check that the results directory is writable");
  }
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

/// One CSV file, built in memory and written whole as a new file (results/new_file.hpp: a link
/// planted at its name is replaced, never followed; a reader never sees half of it).
class CsvOut {
 public:
  CsvOut(const fs::path& path, const std::vector<std::string>& header) : path_(path) {
    for (std::size_t i = 0; i < header.size(); ++i) text_ += (i ? "," : "") + csv_field(header[i]);
    text_ += '\n';
  }
  CsvOut& operator<<(const std::string& field) {
    text_ += (first_ ? "" : ",") + csv_field(field);
    first_ = false;
    return *this;
  }
  CsvOut& operator<<(double v) { return *this << number_text(v, 9); }
  void end_row() {
    text_ += '\n';
    first_ = true;
  }
  void close() { write_whole(path_, text_); }

 private:
  fs::path path_;
  std::string text_;
  bool first_ = true;
};

// ---------------------------------------------------------------------------------------------
// The steps of post_process

/// The uniform grid the record is analysed on; a warning when it had to be resampled onto it.
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

/// What every record is measured with: its grid, the options, the spectrum analyzers (Hann for
/// the amplitude spectra, rectangular for the band powers) and the third-octave bands.
struct Measuring {
  Measuring(const UniformGrid& g, const PostOptions& o)
      : grid(g),
        options(o),
        hann(g.count, Window::kHann),
        rect(g.count, Window::kRectangular),
        bands(resolved_bands(third_octave_bands(o.third_octave_f_min, o.third_octave_f_max),
                             g.count, g.dt)) {}
  const UniformGrid& grid;
  const PostOptions& options;
  SpectrumAnalyzer hann, rect;
  const std::vector<ThirdOctaveBand> bands;
};

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

/// Every receiver measured, in rows by distance (the PPV-versus-distance table), as
/// ppv_versus_distance orders them.
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

/// The receivers whose vertical velocity gets a CWT (indices into results): those the options
/// name, else the nearest to each of the CWT distances.
std::vector<std::size_t> choose_cwt_receivers(const std::vector<ReceiverResult>& results,
                                              const PostOptions& options,
                                              const fs::path& results_dir) {
  std::vector<std::size_t> cwt_of;
  if (options.cwt_receivers.empty()) {
    std::vector<Receiver> ordered;
    for (const ReceiverResult& rr : results) ordered.push_back(*rr.rx);
    return default_cwt_receivers(ordered, options.cwt_distances);
  }
  for (const std::string& name : options.cwt_receivers) {
    const auto it = std::find_if(results.begin(), results.end(),
                                 [&](const ReceiverResult& rr) { return rr.rx->name == name; });
    if (it == results.end()) {
      std::vector<std::string> names;
      for (const ReceiverResult& rr : results) names.push_back(rr.rx->name);
      throw std::runtime_error("CWT receiver '" + name + "' is not in receivers.csv in " +
                               quoted(results_dir) + "; its receivers are " + list_names(names) +
                               ". Name one of them");
    }
    cwt_of.push_back(static_cast<std::size_t>(it - results.begin()));
  }
  return cwt_of;
}

/// The CWT's options within the record's sampling: f_max at most 0.4 of the sampling rate, f_min
/// raised to what the allowed zero padding reaches (each change a warning); cwt_of is emptied
/// when no frequency remains.
CwtOptions cwt_options_for(const PostOptions& options, const UniformGrid& grid,
                           std::vector<std::size_t>& cwt_of, std::vector<std::string>& warnings) {
  const std::size_t n = grid.count;
  CwtOptions cwt_options;
  cwt_options.omega0 = options.cwt_omega0;
  cwt_options.f_min = options.cwt_f_min;
  cwt_options.f_max = std::min(options.cwt_f_max, 0.4 / grid.dt);
  cwt_options.n_freq = options.cwt_n_freq;
  cwt_options.time_stride = std::max<std::size_t>(
      1, (n + options.cwt_max_times - 1) / std::max<std::size_t>(1, options.cwt_max_times));
  if (cwt_options.f_max < options.cwt_f_max)
    warnings.push_back("CWT: f_max lowered from " + number_text(options.cwt_f_max, 9) + " Hz to " +
                       number_text(cwt_options.f_max, 9) + " Hz (0.4 of the sampling rate)");
  // The zero padding for f_min's wavelet is 6 scales, 5.8 s at 1 Hz whatever the record's
  // length: a step of 1e-300 s asked for 1e300 samples (found by the post fuzz target,
  // docs/fuzzing.md). Beyond 64 records (and 65536 samples: 1 Hz at steps of 89 us or more) the
  // wavelet at f_min outlasts the record tenfold and its |W| is all cone of influence: f_min rises
  // to the lowest frequency within that padding (it falls as 1 / f).
  const double padding_allowed =
      std::min(kMaxCwtPadding, std::max(64.0 * static_cast<double>(n), 65536.0));
  if (const double padding = cwt_padding(grid.dt, cwt_options);
      !cwt_of.empty() && padding > padding_allowed) {
    const double raised = cwt_options.f_min * padding / padding_allowed;
    warnings.push_back("CWT: f_min raised from " + number_text(cwt_options.f_min, 9) + " Hz to " +
                       number_text(raised, 9) + " Hz: at the record's step of " +
                       number_text(grid.dt, 9) + " s its wavelet needs " + number_text(padding, 9) +
                       " samples of zero padding, more than " + number_text(padding_allowed, 9) +
                       " (64 times the record's samples, at least 65536)");
    cwt_options.f_min = raised;
  }
  if (!cwt_of.empty() && !(cwt_options.f_min < cwt_options.f_max)) {
    warnings.push_back("CWT skipped: f_min = " + number_text(cwt_options.f_min, 9) +
                       " Hz is not below f_max = " + number_text(cwt_options.f_max, 9) + " Hz");
    cwt_of.clear();
  }
  return cwt_options;
}

std::vector<std::string> ppv_header() {
  std::vector<std::string> header = {"receiver", "x [m]", "distance [m]", "depth [m]",
                                     "PPV_z [m/s]", "t(PPV_z) [s]", "PPV_3c [m/s]",
                                     "PPV_max_component [m/s]", "component", "f_dom [Hz]",
                                     "KB_F,max [m/s]", "v_eff,F,max [m/s]", "v_rms_z [m/s]",
                                     // The resolved band (nan where the soil does not say).
                                     "f_resolved [Hz]", "energy_z above f_resolved [-]",
                                     "PPV_z resolved [m/s]", "PPV_3c resolved [m/s]"};
  for (auto line : kDinLines) {
    header.push_back(name(line) + " [m/s]");
    header.push_back("PPV / " + name(line) + " [-]");
  }
  for (auto line : kBsLines) {
    header.push_back(name(line) + " [m/s]");
    header.push_back("PPV / " + name(line) + " [-]");
  }
  // Within the resolved band: the other indicators of the low-passed record.
  header.push_back("KB_F,max resolved [m/s]");
  header.push_back("f_dom resolved [Hz]");
  for (auto line : kDinLines) header.push_back("PPV / " + name(line) + " resolved [-]");
  for (auto line : kBsLines) header.push_back("PPV / " + name(line) + " resolved [-]");
  return header;
}

/// ppv.csv: a row per receiver, by distance.
void write_ppv_csv(const std::vector<ReceiverResult>& results, PostResult& result) {
  CsvOut out(result.directory / "ppv.csv", ppv_header());
  for (const ReceiverResult& rr : results) {
    const ComponentResult& g = rr.components[rr.governing];
    out << rr.rx->name << rr.rx->x << rr.rx->distance << rr.rx->depth << rr.ppv_z << rr.t_ppv_z
        << rr.ppv_3c << g.peak.value << g.component << g.dominant_f << rr.kb_f_max << rr.v_eff_max
        << rr.vz().v_rms << rr.rx->resolved_f << rr.energy_above_resolved << rr.ppv_z_resolved
        << rr.ppv_3c_resolved;
    for (const GuideCheck& c : rr.din) out << c.guide << c.ratio;
    for (const GuideCheck& c : rr.bs) out << c.guide << c.ratio;
    out << rr.kb_f_max_resolved << rr.dominant_f_resolved;
    for (const GuideCheck& c : rr.din_resolved) out << c.ratio;
    for (const GuideCheck& c : rr.bs_resolved) out << c.ratio;
    out.end_row();
  }
  out.close();
  result.files.push_back(result.directory / "ppv.csv");
}

/// spectra.csv: the amplitude spectra of every component up to f_max, a column each.
void write_spectra_csv(const std::vector<ReceiverResult>& results, double f_max,
                       PostResult& result) {
  std::vector<std::string> header = {"f [Hz]"};
  for (const ReceiverResult& rr : results)
    for (const ComponentResult& c : rr.components)
      header.push_back(rr.rx->name + " " + c.component + " [m/s]");
  CsvOut out(result.directory / "spectra.csv", header);
  const Spectrum& first = results.front().components.front().amplitude;
  for (std::size_t k = 0; k < first.values.size(); ++k) {
    if (first.frequency(k) > f_max) break;
    out << first.frequency(k);
    for (const ReceiverResult& rr : results)
      for (const ComponentResult& c : rr.components) out << c.amplitude.values[k];
    out.end_row();
  }
  out.close();
  result.files.push_back(result.directory / "spectra.csv");
}

/// third_octave.csv: a row per band, the levels of every component in dB re the reference.
void write_third_octave_csv(const std::vector<ReceiverResult>& results,
                            const std::vector<ThirdOctaveBand>& bands, double velocity_reference,
                            PostResult& result) {
  const std::string ref_label = "dB re " + number_text(velocity_reference, 9) + " m/s";
  std::vector<std::string> header = {"band [Hz]", "f_m [Hz]", "f_lower [Hz]", "f_upper [Hz]"};
  for (const ReceiverResult& rr : results)
    for (const ComponentResult& c : rr.components)
      header.push_back(rr.rx->name + " " + c.component + " L_v [" + ref_label + "]");
  CsvOut out(result.directory / "third_octave.csv", header);
  for (std::size_t b = 0; b < bands.size(); ++b) {
    out << bands[b].nominal << bands[b].centre << bands[b].lower << bands[b].upper;
    for (const ReceiverResult& rr : results)
      for (const ComponentResult& c : rr.components) out << c.bands[b].level;
    out.end_row();
  }
  out.close();
  result.files.push_back(result.directory / "third_octave.csv");
}

/// cwt_<name>.csv for each chosen receiver (names made distinct); post.json's "cwt" entries.
json write_scalograms(const std::vector<ReceiverResult>& results,
                      const std::vector<std::size_t>& cwt_of, const UniformGrid& grid,
                      const CwtOptions& cwt_options, PostResult& result) {
  json cwt_json = json::array();
  if (cwt_of.empty()) return cwt_json;
  MorletCwt cwt(grid.count, grid.dt, cwt_options);
  std::set<std::string> used;
  for (std::size_t i : cwt_of) {
    const ReceiverResult& rr = results[i];
    const Scalogram s = cwt.transform(rr.vz().v);
    std::string file = file_name_for(rr.rx->name);
    for (int k = 2; used.count(file); ++k)
      file = file_name_for(rr.rx->name + "_" + std::to_string(k));
    used.insert(file);
    std::vector<std::string> header = {"t [s]", "f_coi [Hz]"};
    for (double f : s.frequency) header.push_back("|W| " + number_text(f, 9) + " Hz [m/s]");
    CsvOut out(result.directory / file, header);
    for (std::size_t j = 0; j < s.time.size(); ++j) {
      out << s.time[j] << s.coi_frequency[j];
      for (std::size_t f = 0; f < s.frequency.size(); ++f) out << s.at(f, j);
      out.end_row();
    }
    out.close();
    result.files.push_back(result.directory / file);
    double w_max = 0.0;
    for (double w : s.magnitude) w_max = std::max(w_max, w);
    cwt_json.push_back({{"receiver", rr.rx->name},
                        {"component", "vz"},
                        {"file", file},
                        {"max_abs_w_m_s", number_or_null(w_max)}});
  }
  return cwt_json;
}

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

/// What post_process found, for post.json.
struct Findings {
  const RunRecord& run;
  const UniformGrid& grid;
  const std::vector<ThirdOctaveBand>& bands;
  const std::vector<ReceiverResult>& receivers;
  const CwtOptions& cwt_options;
};

/// post.json: the numbers of the CSV files with the options, the sampling and the files written
/// (the report is also result.report).
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
