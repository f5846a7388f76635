// One-sided spectra of a real, uniformly sampled record with FFTW (post/fft.hpp), the whole
// record in one transform (no averaging: a pass-by is a transient).
//
// Scaling, for N samples x_n, window w_n and X_k = sum_n w_n x_n exp(-2 pi i k n / N), at the
// frequencies f_k = k / (N dt), k = 0 .. floor(N/2):
//   amplitude  A_k = c_k |X_k| / sum_n w_n,          c_0 = 1, c_{N/2} = 1 (N even), else 2;
//   power      P_k = c_k |X_k|^2 / (N sum_n w_n^2).
// A_k is "peak" scaled with the window's coherent gain corrected: a sine of amplitude A at a bin
// frequency gives A_k = A (between bins the Hann window reads low by at most 15.1 %, i.e.
// 1.42 dB, at half a bin: the scalloping loss |W(1/2)|/|W(0)| = (2/pi)/(3/4) = 0.8488).
// P_k is the mean square [unit^2] the bin holds, with the window's energy corrected: with the
// rectangular window sum_k P_k is exactly the record's mean square (Parseval), and a sine of
// amplitude A contributes A^2/2 in total to the bins around its frequency.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "post/fft.hpp"

namespace rumble::post {

enum class Window {
  kRectangular,
  kHann,  // periodic ("DFT-even") Hann, w_n = 0.5 (1 - cos(2 pi n / N)): sum w = N/2,
          // sum w^2 = 3N/8
};

/// A one-sided spectrum: values[k] at frequency k df, k = 0 .. N/2.
struct Spectrum {
  double df = 0.0;             // Hz, 1 / (N dt)
  std::vector<double> values;  // amplitude [signal unit] or power [signal unit^2]

  double frequency(std::size_t k) const { return static_cast<double>(k) * df; }
};

/// Spectra of records of one length: the FFT plan and the window are made once and reused for
/// every record (every receiver and component of a run has the same length).
class SpectrumAnalyzer {
 public:
  SpectrumAnalyzer(std::size_t n, Window window);

  std::size_t size() const { return fft_.size(); }
  /// Peak amplitude spectrum A_k (see the file comment); x.size() must be size().
  Spectrum amplitude(std::span<const double> x, double dt);
  /// Power spectrum P_k (mean square per bin, see the file comment); x.size() must be size().
  Spectrum power(std::span<const double> x, double dt);

 private:
  /// The one-sided spectrum of x: |X_k|^power / divisor, doubled but for DC and Nyquist (which have
  /// no mirror bin).
  Spectrum one_sided(std::span<const double> x, double dt, int power, double divisor);
  RealFft fft_;
  std::vector<double> window_;
  double sum_w_ = 0.0, sum_w2_ = 0.0;
};

/// The frequency of the largest amplitude at or above f_min [Hz] (DIN 4150-3 and BS 7385-2 read
/// guide values at this "dominant" frequency), refined between bins by a parabola through the
/// logarithms of the peak bin and its neighbours (a Gaussian fit: within 0.02 bin for a
/// Hann-windowed sine at any offset). NaN when no bin above f_min has a non-zero amplitude.
double dominant_frequency(const Spectrum& amplitude, double f_min);

}  // namespace rumble::post
