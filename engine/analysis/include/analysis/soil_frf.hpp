// Frequency response of a soil at the track's footprints: the driving-point receptance of the
// middle footprint and its transfer receptances to the next footprints along the track, read
// through the soil plugin's exact frequency_response (no time stepping).
#pragma once

#include <complex>
#include <filesystem>
#include <string>
#include <vector>

namespace rumble {

class SoilInstance;

struct SoilFrf {
  std::string label;              // e.g. "clm" or a scenario name
  std::size_t centre = 0;         // index of the driven footprint
  std::vector<double> frequency;  // Hz
  /// receptance[k][j]: u(centre + k) / F(centre) at frequency[j] [m/N], k = 0 driving point.
  std::vector<std::vector<std::complex<double>>> receptance;
};

/// n_points frequencies from f_min to f_max [Hz], equally spaced in log(f).
std::vector<double> log_frequencies(double f_min, double f_max, int n_points);

/// Returns false (and leaves frf empty) when the soil offers no frequency response. Throws
/// Interrupted (where it stopped, what is kept) when Ctrl-C or SIGTERM came: the commands that
/// call it install the interrupt handler once their soil is built (a first Ctrl-C while gmsh
/// meshes is honoured only after it).
bool soil_frf(SoilInstance& soil, std::size_t n_footprints, const std::vector<double>& frequency,
              std::size_t transfer_terms, SoilFrf& frf);

/// CSV: f [Hz], then |H_0k| [m/N] and phase(H_0k) [deg] for every term k.
void write_frf_csv(const std::filesystem::path& file, const SoilFrf& frf);

}  // namespace rumble
