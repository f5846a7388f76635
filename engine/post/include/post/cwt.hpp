// Continuous wavelet transform (CWT) with the Morlet wavelet, computed with FFTW as in Torrence
// & Compo (1998), "A practical guide to wavelet analysis", Bull. Amer. Meteor. Soc. 79(1) 61-78:
// the FFT of the zero-padded signal times the wavelet's Fourier transform at each scale, then an
// inverse FFT.
//
// Wavelet and normalisation. With X(omega) the signal's Fourier transform and omega0 the
// wavelet's centre frequency (6 by default, T&C's choice), the transform at scale s [s] is
//   W(s, t) = F^-1[ X(omega) Psi(s omega) ](t),
//   Psi(s omega) = 2 exp((eta_F - omega0)^2 / 2) exp(-(s omega - omega0)^2 / 2) for omega > 0,
//                  0 for omega <= 0 (the analytic Morlet, as T&C's Heaviside factor),
//   eta_F = (omega0 + sqrt(2 + omega0^2)) / 2.
// In the time domain this is W(s, t) = (K / s) int x(tau) conj(psi0((tau - t) / s)) dtau with
// T&C's psi0(eta) = pi^(-1/4) exp(i omega0 eta) exp(-eta^2/2) (analytic part) and
// K = 2 pi^(1/4) exp((eta_F - omega0)^2 / 2) / sqrt(2 pi): an "L1" normalisation (1/s, not
// T&C's energy-preserving 1/sqrt(s)), so that a tone keeps its amplitude at every scale.
//
// Scale and frequency. A scale s is labelled with T&C's Fourier frequency (their Table 1)
//   f = (omega0 + sqrt(2 + omega0^2)) / (4 pi s) = eta_F / (2 pi s)   (f ~ 0.9676 / s for 6).
// A tone A cos(2 pi f1 t) then gives |W| = A exp((eta_F - omega0)^2/2 - (eta_F f1/f - omega0)^2/2)
// along the frequency axis: exactly A at f = f1 (the constant above is chosen for that), and a
// maximum of A exp((eta_F - omega0)^2 / 2) = 1.0034 A at f = f1 eta_F / omega0 = 1.0137 f1 for
// omega0 = 6 (the 1/s normalisation puts the maximum over scales at s omega = omega0, while T&C's
// frequency marks the maximum of their 1/sqrt(s) one). |W| is in the signal's unit (m/s).
//
// Edges. The signal is padded with zeros to at least N + 6 s_max / dt samples, so that the
// circular convolution never wraps the record's end onto its start (the wavelet's envelope
// exp(-t^2 / (2 s^2)) is below 2e-8 beyond 6 s). The zeros still bias |W| low near the edges:
// the cone of influence (T&C section 3g) is where the wavelet's e-folding time sqrt(2) s reaches
// past the record's edge: at time t, with d = min(t - t_first, t_last - t), frequencies below
//   f_coi(t) = eta_F / (2 pi d / sqrt(2))
// are affected (f_coi is clamped to the Nyquist frequency 1 / (2 dt) at the edges).
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "post/fft.hpp"
#include "post/time_series.hpp"

namespace rumble::post {

struct CwtOptions {
  double omega0 = 6.0;          // Morlet centre frequency, > 0 (>= 5 keeps it admissible)
  double f_min = 1.0;           // Hz, lowest analysed frequency, > 0
  double f_max = 100.0;         // Hz, highest, < Nyquist frequency 1 / (2 dt)
  std::size_t n_freq = 64;      // frequencies, log-spaced from f_min to f_max (>= 1)
  std::size_t time_stride = 1;  // keep every time_stride-th time sample in the result
};

/// |W| on a grid of frequencies (rows) and times (columns).
struct Scalogram {
  std::vector<double> frequency;      // Hz, ascending
  std::vector<double> scale;          // s, scale[i] = eta_F / (2 pi frequency[i])
  std::vector<double> time;           // s, the kept samples' times
  std::vector<double> coi_frequency;  // Hz, f_coi at each kept time (below: edge-affected)
  std::vector<double> magnitude;      // |W| [signal unit], row-major: [i_freq * n_time + i_time]

  double at(std::size_t i_freq, std::size_t i_time) const {
    return magnitude[i_freq * time.size() + i_time];
  }
};

/// f = (omega0 + sqrt(2 + omega0^2)) / (4 pi s) [Hz] for a scale s [s] (Torrence & Compo).
double morlet_frequency(double scale, double omega0);
/// The inverse: the scale [s] whose Fourier frequency is f [Hz].
double morlet_scale(double frequency, double omega0);
/// n values from lo to hi equally spaced in log (lo alone when n = 1).
std::vector<double> log_spaced(double lo, double hi, std::size_t n);

/// The zero padding [samples] a transform at time step dt adds for options.f_min (6 scales of
/// f_min, see "Edges"), before rounding to an FFT-friendly size; a double, as it can exceed any
/// size when dt is tiny.
double cwt_padding(double dt, const CwtOptions& options);
/// Most padding MorletCwt takes: 2^26 samples (1 GiB per complex FFT buffer). A record of a
/// tiny step asks for more; the lowest frequency f_min must then rise (post_process raises it).
inline constexpr double kMaxCwtPadding = 67108864.0;

/// A Morlet CWT for records of one length and time step: the padded FFT plans and the wavelet's
/// spectra are made once, then transform() runs per record (one forward and n_freq inverse
/// FFTs). Options out of range throw std::invalid_argument saying which and why (padding beyond
/// kMaxCwtPadding included).
class MorletCwt {
 public:
  MorletCwt(std::size_t n, double dt, const CwtOptions& options);

  std::size_t padded_size() const { return forward_.size(); }
  /// The scalogram of x (x.size() must be the n given at construction; x.t0 sets the times).
  Scalogram transform(const TimeSeries& x);

 private:
  std::size_t n_;
  double dt_;
  CwtOptions options_;
  std::vector<double> frequency_, scale_;
  std::vector<std::vector<double>> kernel_;  // Psi(s omega_k) per frequency, k = 0 .. L/2
  ComplexFft forward_, inverse_;
};

/// One-shot convenience: MorletCwt(x.size(), x.dt, options).transform(x).
Scalogram cwt_morlet(const TimeSeries& x, const CwtOptions& options);

}  // namespace rumble::post
