// One-third-octave band velocity levels L_v [dB], from the record's power spectrum.
//
// Bands (IEC 61260-1, base-10 system): exact mid-band frequencies f_m = 10^(n/10) Hz for
// integer n (n = 0: 1 Hz, n = 12: 15.85 Hz labelled "16"), band edges f_m 10^(-1/20) and
// f_m 10^(+1/20). Adjacent bands share their edges; a spectral bin at f belongs to the band with
// f_lower <= f < f_upper, so each bin is counted once.
//
// Level: the band's mean square is the sum of the power spectrum P_k (post/spectrum.hpp,
// rectangular window: no window weighs a transient's middle against its ends, and the bands
// then add up to the record's mean square exactly, Parseval) over the band's bins; then
//   L_v = 10 log10(mean square / v_ref^2) = 20 log10(v_rms / v_ref)  [dB re v_ref],
// with v_ref = 1e-9 m/s (ISO 1683, the SI reference for vibration velocity) or the US
// reference 1 micro-inch/s = 2.54e-8 m/s, whose levels are called VdB (FTA, "Transit Noise and
// Vibration Impact Assessment"). 1 mm/s RMS is 120 dB re 1e-9 m/s and 91.9 VdB.
// The RMS is over the whole record: for a pass-by, a longer quiet tail lowers the levels
// (10 log10 of the duration ratio); state the record length with the levels.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "post/spectrum.hpp"

namespace rumble::post {

constexpr double kVelocityRefIso1683 = 1e-9;  // m/s, ISO 1683 reference vibration velocity
constexpr double kVelocityRefVdb = 2.54e-8;   // m/s, 1 micro-inch/s, reference of VdB

struct ThirdOctaveBand {
  int index = 0;        // n in f_m = 10^(n/10) Hz
  double centre = 0.0;  // Hz, exact mid-band frequency
  double lower = 0.0;   // Hz, f_m 10^(-1/20)
  double upper = 0.0;   // Hz, f_m 10^(+1/20)
  std::string nominal;  // the preferred label ("1", "1.25", ... "16", "31.5", "63", ...)
};

/// The band of index n.
ThirdOctaveBand third_octave_band(int n);

/// The bands whose mid-band frequency lies in [f_lo, f_hi] Hz (both > 0), ascending.
std::vector<ThirdOctaveBand> third_octave_bands(double f_lo, double f_hi);

/// Of `bands`, those a record of n samples at step dt [s] resolves: the band lies below the
/// Nyquist frequency (upper edge <= 1/(2 dt)) and is at least one bin wide (upper - lower >=
/// 1/(n dt)), so it always holds a bin.
std::vector<ThirdOctaveBand> resolved_bands(const std::vector<ThirdOctaveBand>& bands,
                                            std::size_t n, double dt);

struct BandLevel {
  ThirdOctaveBand band;
  double rms = 0.0;    // signal unit (m/s), RMS of the band's content over the record
  double level = 0.0;  // dB re v_ref; -inf for an empty band
};

/// Band RMS and level from a power spectrum P_k (mean square per bin, SpectrumAnalyzer::power).
std::vector<BandLevel> band_levels(const Spectrum& power, const std::vector<ThirdOctaveBand>& bands,
                                   double v_ref);

/// 20 log10(rms / v_ref) [dB]; -inf for rms = 0. v_ref > 0 (std::invalid_argument otherwise).
double level_db(double rms, double v_ref);

}  // namespace rumble::post
