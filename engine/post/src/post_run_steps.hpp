// What the steps of post_process pass between them (the run as read, its measures, the CWT's
// options): shared by the files that read the run, measure it and write its outputs, and by
// post_run.cpp, which calls them in order. Private to the post room: the interface is
// post/post_run.hpp.
#pragma once

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "post/cwt.hpp"
#include "post/guide_values.hpp"
#include "post/post_run.hpp"
#include "post/ppv.hpp"
#include "post/spectrum.hpp"
#include "post/third_octave.hpp"
#include "post/time_series.hpp"

namespace rumble::post::detail {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// A receiver with more than this share of its vertical energy above its resolved band is warned
// about (docs/post-processing.md, "The resolved band"): its spectral indicators are then mostly
// the mesh's above the band.
constexpr double kUnresolvedShare = 0.2;
// Its raw PPV is called the mesh's when the PPV within the band is less than this share of it
// (else the warning says how much of it the band keeps).
constexpr double kResolvedPpvShare = 0.5;
constexpr const char* kComponents[3] = {"vx", "vy", "vz"};
constexpr Din4150Line kDinLines[3] = {Din4150Line::kCommercial, Din4150Line::kDwelling,
                                      Din4150Line::kSensitive};
constexpr Bs7385Line kBsLines[2] = {Bs7385Line::kReinforced, Bs7385Line::kUnreinforced};

// JSON has no NaN or infinity: null stands for "not available".
inline json number_or_null(double v) {
  return std::isfinite(v) ? json(v) : json(nullptr);
}

inline std::string quoted(const fs::path& p) {
  return "'" + p.string() + "'";
}

// ---------------------------------------------------------------------------------------------
// Reading the run (post_inputs.cpp)

struct Receiver {
  std::string name;
  double x = kNaN, distance = kNaN, depth = 0.0;  // m
  double resolved_f = kNaN;  // Hz, the band the soil carries here (summary.json; NaN: unknown)
  // Column index in the CSV table per component vx, vy, vz; vertical-only receivers have vz.
  std::optional<std::size_t> column[3];
  bool three_component() const { return column[0] && column[1] && column[2]; }
};

struct RunRecord {
  CsvTable table;
  std::vector<Receiver> receivers;
  std::string form;  // "probes" or "distances"
};

/// The receivers.csv of the run in `dir` with its receivers, placed from its summary.json;
/// throws naming what is missing and the fix.
RunRecord read_run(const fs::path& dir);

// Cuts the record before the first non-finite velocity (a diverged run) and says so. A run that
// completed writes finite numbers only: then the file is blamed, not the run.
void cut_at_divergence(RunRecord& run, std::vector<std::string>& warnings, const fs::path& dir);

/// "'a', 'b', ... (n in all)", at most `max` names; "none" for none.
std::string list_names(const std::vector<std::string>& names, std::size_t max = 8);

// ---------------------------------------------------------------------------------------------
// Measuring (post_measures.cpp)

struct ComponentResult {
  std::string component;  // vx, vy, vz
  TimeSeries v;
  Peak peak;
  double dominant_f = kNaN;                                               // Hz
  double kb_f_max = 0.0, t_kb_f_max = 0.0, v_eff_max = 0.0, v_rms = 0.0;  // m/s, s
  Spectrum amplitude;
  std::vector<BandLevel> bands;
};

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

/// The uniform grid the record is analysed on; a warning when it had to be resampled onto it.
UniformGrid record_grid(const CsvTable& table, const fs::path& results_dir,
                        const PostOptions& options, std::vector<std::string>& warnings);

/// Throws when the band levels' reference velocity is not > 0.
void check_velocity_reference(const PostOptions& options);

/// Every receiver measured, in rows by distance (the PPV-versus-distance table), as
/// ppv_versus_distance orders them.
std::vector<ReceiverResult> measure_receivers(const RunRecord& run, Measuring& m,
                                              std::vector<std::string>& warnings);

// ---------------------------------------------------------------------------------------------
// The scalograms' receivers and options (post_cwt_plan.cpp)

/// The receivers whose vertical velocity gets a CWT (indices into results): those the options
/// name, else the nearest to each of the CWT distances.
std::vector<std::size_t> choose_cwt_receivers(const std::vector<ReceiverResult>& results,
                                              const PostOptions& options,
                                              const fs::path& results_dir);

/// The CWT's options within the record's sampling: f_max at most 0.4 of the sampling rate, f_min
/// raised to what the allowed zero padding reaches (each change a warning); cwt_of is emptied
/// when no frequency remains.
CwtOptions cwt_options_for(const PostOptions& options, const UniformGrid& grid,
                           std::vector<std::size_t>& cwt_of, std::vector<std::string>& warnings);

// ---------------------------------------------------------------------------------------------
// Writing the CSV files (post_outputs.cpp)

/// Writes `text` as the new file `path` (through path + ".tmp"); throws naming the file.
void write_whole(const fs::path& path, const std::string& text);

/// The directory `path`, created when missing; a file or link standing at its name is replaced,
/// never followed.
void make_directory(const fs::path& path);

/// ppv.csv: a row per receiver, by distance.
void write_ppv_csv(const std::vector<ReceiverResult>& results, PostResult& result);

/// spectra.csv: the amplitude spectra of every component up to f_max, a column each.
void write_spectra_csv(const std::vector<ReceiverResult>& results, double f_max,
                       PostResult& result);

/// third_octave.csv: a row per band, the levels of every component in dB re the reference.
void write_third_octave_csv(const std::vector<ReceiverResult>& results,
                            const std::vector<ThirdOctaveBand>& bands, double velocity_reference,
                            PostResult& result);

/// cwt_<name>.csv for each chosen receiver (names made distinct); post.json's "cwt" entries.
json write_scalograms(const std::vector<ReceiverResult>& results,
                      const std::vector<std::size_t>& cwt_of, const UniformGrid& grid,
                      const CwtOptions& cwt_options, PostResult& result);

// ---------------------------------------------------------------------------------------------
// Writing post.json (post_report.cpp)

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
                     json cwt_json, PostResult& result);

}  // namespace rumble::post::detail
