// Post-processing of a results directory as `rumble run` writes it, without rerunning: reads
// receivers.csv (and summary.json for the receivers' positions) and writes RESULTS_DIR/post/:
//   ppv.csv           per receiver: PPV (vertical, three-component, largest component), dominant
//                     frequency, KB_F,max and v_eff,F,max (DIN 4150-2), RMS, and the DIN 4150-3 /
//                     BS 7385-2 guide values at the dominant frequency with the ratios PPV/guide;
//                     rows by distance from the track (the PPV-versus-distance table);
//   spectra.csv       one-sided amplitude spectra (Hann) of every component;
//   third_octave.csv  one-third-octave band levels L_v of every component;
//   cwt_<name>.csv    Morlet scalograms |W| of the vertical velocity at chosen receivers;
//   post.json         the same numbers, the options and the sampling, for scripts and reports.
// docs/post-processing.md describes every indicator, formula and column.
//
// receivers.csv comes in two forms: receivers of soils that offer probes (engine/run/
// probe_recorder.cpp) have columns "<name> vx [m/s]", "<name> vy [m/s]", "<name> vz [m/s]",
// "<name> ux [m]", ... and summary.json's "ppv" entries give name, x_m, distance_m, depth_m; the
// older surface receivers (engine/run/src/run_recorder.cpp) have one vertical velocity column
// "d=<distance> m [m/s]" each. Problems throw std::runtime_error saying what, where, the value
// and the fix.
#pragma once

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "post/third_octave.hpp"

namespace rumble::post {

struct PostOptions {
  /// Receivers (names as in receivers.csv, e.g. "d=2.5 m") whose vertical velocity gets a CWT;
  /// empty: for each of cwt_distances the receiver nearest to it (surface ones first).
  std::vector<std::string> cwt_receivers;
  std::vector<double> cwt_distances = {2.5, 5.0};  // m, the seed paper's Figures 6 and 7
  double cwt_f_min = 1.0;                          // Hz
  double cwt_f_max = 200.0;                        // Hz, lowered to 0.4 / dt when above it
  std::size_t cwt_n_freq = 64;                     // log-spaced frequencies
  double cwt_omega0 = 6.0;                         // Morlet centre frequency
  std::size_t cwt_max_times = 2000;  // rows of a cwt_<name>.csv at most (every k-th sample)
  double velocity_reference = kVelocityRefIso1683;  // m/s, of the band levels (VdB: 2.54e-8)
  double spectrum_f_max = 500.0;                    // Hz, spectra.csv stops here (or at Nyquist)
  double third_octave_f_min = 1.0;                  // Hz, lowest band centre
  double third_octave_f_max = 250.0;                // Hz, highest band centre
  double dominant_f_min = 1.0;  // Hz, the dominant frequency is searched from here
  double max_step_ratio = 4.0;  // largest recorded step / median step before refusing
};

struct PostResult {
  std::filesystem::path directory;           // RESULTS_DIR/post
  std::vector<std::filesystem::path> files;  // what was written, in that directory
  std::vector<std::string> warnings;         // what was tolerated (resampling, divergence, ...)
  nlohmann::json report;                     // the content of post.json
};

/// The options a scenario's outputs.post gives (schema defaults for what it leaves out), over
/// `base`; a scenario without outputs.post gives base.
PostOptions options_from_scenario(const nlohmann::json& scenario, PostOptions base = {});

/// The options of the run in results_dir (`rumble post`): those of the scenario its summary.json
/// records, the defaults where there is none or summary.json cannot be read or used
/// (post_process names what it lacks).
PostOptions options_from_summary(const std::filesystem::path& results_dir);

/// Computes every indicator for the run in results_dir and writes RESULTS_DIR/post/.
PostResult post_process(const std::filesystem::path& results_dir, const PostOptions& options = {});

}  // namespace rumble::post
