// What a receiver's record says within the band its soil resolves (docs/post-processing.md,
// "The resolved band"). A FEM soil carries waves up to a frequency set by its elements along
// the path from the load (ABI 1.3 probe_resolution, in summary.json's `resolved_f_hz`); above
// it the motion is the mesh's, not the ground's. Two numbers tell how much of a record that is,
// and what is left without it:
//   - the share of the record's energy (mean square) above the resolved frequency, from the
//     rectangular power spectrum (whose bins add up to the mean square);
//   - the record low-passed at the resolved frequency with zero phase: its FFT times the gain of
//     a 4th-order Butterworth low-pass, 1 / sqrt(1 + (f / f_c)^8) (-3 dB at f_c, -24 dB per
//     octave above it), and back; the record is zero-padded to twice its length so that the
//     filter's response does not wrap around. Zero phase keeps the peak where it was.
#pragma once

#include <span>
#include <vector>

#include "post/spectrum.hpp"

namespace rumble::post {

/// Share [-] of the power spectrum's total above f_hz [Hz] (0 for a silent record).
double energy_share_above(const Spectrum& power, double f_hz);

/// The samples v at spacing dt [s] low-passed at f_c [Hz] with zero phase (above).
std::vector<double> zero_phase_low_pass(std::span<const double> v, double dt, double f_c);

/// The Butterworth order of zero_phase_low_pass.
inline constexpr int kLowPassOrder = 4;

}  // namespace rumble::post
