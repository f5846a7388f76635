// Frequency-flat material damping by generalized Maxwell (Zener) mechanisms: memory variables,
// the constant-Q damping of seismology (Emmerich and Korn 1987; docs/numerics.md §4.3), written on
// the assembled stiffness. With every mechanism scaling the whole elasticity tensor (the same
// ratio for P and S waves, as Rayleigh's a1 K), each one's memory is a nodal vector:
//   internal force  K (w + sum_l c_l z_l),   z_l' + omega_l z_l = w',
// so the complex modulus is K (1 + sum_l c_l i w / (omega_l + i w)): K at rest (the statics solve
// K), K (1 + sum c_l) at high frequency. The weights c_l are fitted by least squares so that the
// damping ratio Im / (2 Re) is `ratio` over [f_low, f_high] (tested: within 2.8 % of it with three
// mechanisms on 5-100 Hz at 2 %, 3.6 % at 5 %, 3.1 % with four on 1-200 Hz); outside the band it
// falls (as w at low, 1 / w at high frequency) where Rayleigh's grows. The plugin assembles K with
// E over Re(modulus) at the band's centre (DampingRequest::relaxed_modulus_factor).
//
// In the central difference each mechanism is integrated exactly for a displacement linear over
// the step, z_l <- e_l z_l + g_l dw, e_l = exp(-omega_l dt), g_l = (1 - e_l) / (omega_l dt), at
// the step's new displacement: unlike a1 K v+ nothing lags, and the stable step is the undamped
// one of the unrelaxed stiffness, 2 / (omega_max sqrt(1 + sum c_l)) (checked mode by mode and on
// a mesh: docs/fem-soil.md §4.4).
#pragma once

#include <complex>
#include <vector>

namespace rumble::fem {

struct MaxwellDamping {
  static constexpr int kMaxMechanisms = 8;  // (the explicit step keeps their factors on its stack)

  std::vector<double> rates;    // omega_l [rad/s], log-spaced over the band
  std::vector<double> weights;  // c_l [-]

  /// The mechanisms whose damping ratio is `ratio` over [f_low, f_high] [Hz]: `mechanisms`
  /// relaxation rates log-spaced from f_low to f_high, the weights by least squares at four
  /// frequencies per mechanism, log-spaced over the band.
  static MaxwellDamping fit(double ratio, double f_low, double f_high, int mechanisms);

  int mechanisms() const { return static_cast<int>(rates.size()); }
  /// The largest |ratio_at / ratio - 1| over [f_low, f_high] [Hz] (64 log-spaced frequencies).
  double band_error(double ratio, double f_low, double f_high) const;
  /// Whether every weight is positive: each mechanism then dissipates (a negative one, which a
  /// narrow band with many mechanisms or a high ratio can give, would feed energy in).
  bool dissipative() const;
  /// The complex modulus over the relaxed one at circular frequency omega [rad/s].
  std::complex<double> modulus(double omega) const;
  /// The damping ratio Im / (2 Re) of modulus(omega) [-].
  double ratio_at(double omega) const;
  /// 1 + sum c_l: the unrelaxed (high-frequency) modulus over the relaxed one.
  double unrelaxed() const;
};

}  // namespace rumble::fem
