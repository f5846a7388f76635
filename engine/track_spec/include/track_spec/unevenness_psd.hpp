// Roughness spectra for random rail profiles.
//
// UNITS. Every spectrum here is a ONE-SIDED power spectral density S(Omega) in m^2/(rad/m) of
// the wavenumber Omega = 2 pi / lambda [rad/m], normalized so that the mean square of the
// profile over a band is
//     sigma^2 = integral_{Omega_1}^{Omega_2} S(Omega) dOmega   [m^2].
// The same spectrum per cycle/m (n = 1/lambda) is S_n(n) = 2 pi S(2 pi n) [m^2/(cycle/m)];
// mixing the two is the classic factor-2-pi error, so the synthesis and its tests go through
// integral() only.
//
// FRA1 .. FRA6: US FRA track classes, vertical profile (Garg & Dukkipati, Dynamics of Railway
//   Vehicle Systems, 1984, after the FRA/ENSCO track-geometry surveys; reproduced e.g. in Zhai,
//   Vehicle-Track Coupled Dynamics, 2020, with the same constants):
//     S(Omega) = k A_v Omega_c^2 / (Omega^2 (Omega^2 + Omega_c^2)),  k = 0.25,
//     Omega_c = 0.8245 rad/m,  A_v = 1.2107, 1.0181, 0.6816, 0.5376, 0.2095, 0.0339 cm^2 rad/m
//   for classes 1 .. 6 (class 6 is the best track). S comes out in cm^2/(rad/m): x 1e-4 for m^2.
//   Defined for all Omega > 0; meant for track geometry wavelengths, about 1 to 300 m.
// ISO3095: the rail roughness limit of ISO 3095:2013 Figure 2 (the same 22 values as
//   EN 15610:2009 Annex B.9.2): one-third octave band levels L_i [dB re 1 um] at the band centre
//   wavelengths 40 cm .. 0.315 cm (exact centres lambda_n = 10^(-n/10) m, n = 4 .. 25),
//   17.1 dB at 40 cm down to -11.0 dB at 0.315 cm. A band's mean square is
//   r_i^2 = (1e-6 m)^2 10^(L_i/10) over the band [Omega_i 10^(-1/20), Omega_i 10^(1/20)]
//   (width dOmega_i = 0.2308 Omega_i). S is a power law (straight in log-log) between node values
//   at the band centres, continued beyond the end centres to the outer band edges; the node
//   values start at r_i^2 / dOmega_i and are rescaled until the integral over every band is r_i^2
//   (to 1e-12: the levels are reproduced exactly; the plain r_i^2 / dOmega_i nodes would miss by
//   up to 0.16 dB where the slope of the levels changes). Defined for wavelengths from
//   10^(-2.55) m (2.82 mm) to 10^(-0.35) m (44.7 cm). It is a limit for acoustic (short-wave)
//   roughness, not a track geometry spectrum.
#pragma once

#include <string>
#include <vector>

namespace rumble {

class RoughnessSpectrum {
 public:
  /// FRA track class 1..6; throws std::invalid_argument otherwise.
  static RoughnessSpectrum fra(int track_class);
  /// The ISO 3095:2013 rail roughness limit spectrum.
  static RoughnessSpectrum iso3095();
  /// "FRA1" .. "FRA6" or "ISO3095"; throws std::invalid_argument naming the accepted names.
  static RoughnessSpectrum from_name(const std::string& name);

  /// S(Omega) [m^2/(rad/m)] at Omega > 0 [rad/m].
  double operator()(double omega) const;
  /// integral of S over [omega_lo, omega_hi] [m^2], 0 < omega_lo <= omega_hi, in closed form
  /// (no quadrature error, no cancellation for narrow intervals).
  double integral(double omega_lo, double omega_hi) const;

  /// Wavelength range [m] over which the spectrum is defined (FRA: 0 to infinity).
  double min_wavelength() const { return min_wavelength_; }
  double max_wavelength() const { return max_wavelength_; }
  /// Whether a wavelength lies within that range, with a relative slack of 1e-9 so that the
  /// documented limits, rounded to 3 digits, pass.
  bool above_min(double wavelength) const { return wavelength >= min_wavelength_ * (1.0 - 1e-9); }
  bool below_max(double wavelength) const { return wavelength <= max_wavelength_ * (1.0 + 1e-9); }
  const std::string& name() const { return name_; }

 private:
  RoughnessSpectrum() = default;
  double fra_integral(double a, double b) const;
  double power_law_integral(double a, double b) const;

  std::string name_;
  double min_wavelength_ = 0.0, max_wavelength_ = 0.0;  // m
  // FRA: k A_v [m^2 rad/m] and Omega_c [rad/m].
  double fra_scale_ = 0.0, fra_omega_c_ = 0.0;
  // Power law between nodes (increasing Omega), the ends extended to the validity limits.
  std::vector<double> omega_;     // rad/m
  std::vector<double> psd_;       // m^2/(rad/m)
  std::vector<double> exponent_;  // d ln S / d ln Omega on [omega_i, omega_i+1]
};

}  // namespace rumble
