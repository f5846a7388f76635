// Roughness spectra: FRA class constants and formula, the ISO 3095 band levels, the closed-form
// band integrals against quadrature, and the per-rad/m vs per-cycle/m unit convention.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "expect_message.hpp"
#include "simpson_log.hpp"
#include "track_spec/unevenness_psd.hpp"

namespace rumble {
namespace {

TEST(RoughnessSpectrum, FraClassesFollowTheTabulatedConstants) {
  // Typed here independently of the implementation: A_v [cm^2 rad/m] per class, Omega_c =
  // 0.8245 rad/m, k = 0.25; S in cm^2/(rad/m) -> x 1e-4 for m^2/(rad/m).
  const double av[] = {1.2107, 1.0181, 0.6816, 0.5376, 0.2095, 0.0339};
  const double wc = 0.8245;
  for (int c = 1; c <= 6; ++c) {
    const RoughnessSpectrum s = RoughnessSpectrum::fra(c);
    EXPECT_EQ(s.name(), "FRA" + std::to_string(c));
    for (double w : {0.05, 0.3, 0.8245, 2.0, 6.0, 60.0}) {
      const double expected = 0.25 * av[c - 1] * wc * wc / (w * w * (w * w + wc * wc)) * 1e-4;
      EXPECT_NEAR(s(w), expected, 1e-13 * expected) << c << " " << w;
    }
  }
  // Class 6 is the best track: the spectrum falls with the class number at every wavenumber.
  for (int c = 1; c < 6; ++c)
    EXPECT_GT(RoughnessSpectrum::fra(c)(1.0), RoughnessSpectrum::fra(c + 1)(1.0));
  // FRA5 in SI as printed by other codes (STEM/Zhang 2001 defaults): A_v = 2.095e-5 m^2 rad/m.
  const double w = 1.3;
  EXPECT_NEAR(RoughnessSpectrum::fra(5)(w), 0.25 * 2.095e-5 * wc * wc / (w * w * (w * w + wc * wc)),
              1e-20);
}

TEST(RoughnessSpectrum, FraIntegralIsTheClosedFormAndMatchesQuadrature) {
  // Antiderivative of k A c^2/(W^2 (W^2 + c^2)) = k A (1/W^2 - 1/(W^2 + c^2)):
  //   -k A (1/W + atan(W/c)/c).
  const double kA = 0.25 * 0.5376e-4, c = 0.8245;
  const auto antiderivative = [&](double w) { return -kA * (1.0 / w + std::atan(w / c) / c); };
  const RoughnessSpectrum s = RoughnessSpectrum::fra(4);
  for (auto [a, b] : {std::pair{2 * std::numbers::pi / 30, 2 * std::numbers::pi / 1.0},
                      std::pair{0.1, 0.2}, std::pair{3.0, 50.0}, std::pair{0.01, 100.0}}) {
    const double closed = antiderivative(b) - antiderivative(a);
    EXPECT_NEAR(s.integral(a, b), closed, 1e-12 * closed) << a << " " << b;
    const double quad = simpson_log([&](double w) { return s(w); }, a, b);
    EXPECT_NEAR(s.integral(a, b), quad, 1e-9 * quad) << a << " " << b;
  }
}

TEST(RoughnessSpectrum, NarrowIntervalsKeepFullPrecision) {
  // The synthesis integrates over bins as narrow as 1e-5 of their wavenumber; a naive
  // difference of antiderivatives would lose most digits there (short waves: both terms ~1/W,
  // their difference ~c^2/W^3).
  for (const RoughnessSpectrum& s : {RoughnessSpectrum::fra(2), RoughnessSpectrum::iso3095()}) {
    for (double w : {0.3, 6.0, 60.0, 600.0, 2000.0}) {
      const double b = w + 1e-7 * w, dw = b - w;  // dw exact (Sterbenz)
      const double mid = s(w + 0.5 * dw) * dw;    // midpoint rule, relative error ~ (dw/w)^2
      EXPECT_NEAR(s.integral(w, b), mid, 1e-9 * mid) << s.name() << " " << w;
    }
  }
}

TEST(RoughnessSpectrum, Iso3095ReproducesTheThirdOctaveBandLevels) {
  // ISO 3095:2013 Figure 2 / EN 15610:2009 B.9.2, typed independently: 40 cm .. 0.315 cm.
  const double levels[] = {17.1, 15.0, 13.0, 11.0, 9.0,  7.0,  4.9,  2.9,  0.9,  -1.1,  -3.2,
                           -5.0, -5.6, -6.2, -6.8, -7.4, -8.0, -8.6, -9.2, -9.8, -10.4, -11.0};
  const RoughnessSpectrum s = RoughnessSpectrum::iso3095();
  for (int i = 0; i < 22; ++i) {
    const double lambda = std::pow(10.0, -(4 + i) / 10.0);  // base-10 third-octave centre
    const double w = 2.0 * std::numbers::pi / lambda;
    // Band [W 10^-0.05, W 10^0.05]; L = 10 log10(r^2 / (1 um)^2).
    const double ms = s.integral(w * std::pow(10.0, -0.05), w * std::pow(10.0, 0.05));
    EXPECT_NEAR(10.0 * std::log10(ms / 1e-12), levels[i], 1e-9) << lambda;
    // At the centre S stays near the band's flat-spectrum value r^2 / dOmega (within 0.3 dB:
    // the node correction only compensates the curvature of the levels).
    const double width = w * (std::pow(10.0, 0.05) - std::pow(10.0, -0.05));
    const double r2 = 1e-12 * std::pow(10.0, levels[i] / 10.0);
    EXPECT_NEAR(10.0 * std::log10(s(w) * width / r2), 0.0, 0.3) << lambda;
  }
  EXPECT_NEAR(s.max_wavelength(), std::pow(10.0, -0.35), 1e-15);
  EXPECT_NEAR(s.min_wavelength(), std::pow(10.0, -2.55), 1e-15);
  // Power law between centres: quadrature over the whole range agrees with integral().
  const double a = 2 * std::numbers::pi / s.max_wavelength(),
               b = 2 * std::numbers::pi / s.min_wavelength();
  const double quad = simpson_log([&](double w) { return s(w); }, a, b, 200000);
  EXPECT_NEAR(s.integral(a, b), quad, 1e-6 * quad);
}

TEST(RoughnessSpectrum, PerCycleSpectrumIsTwoPiTimesPerRadian) {
  // The unit convention: sigma^2 = int S(Omega) dOmega = int S_n(n) dn with
  // S_n(n) = 2 pi S(2 pi n). Using S in place of S_n (or the reverse) is off by 2 pi.
  const RoughnessSpectrum s = RoughnessSpectrum::fra(3);
  const double n_lo = 1.0 / 30.0, n_hi = 1.0 / 1.0;
  const double per_cycle = simpson_log(
      [&](double n) { return 2.0 * std::numbers::pi * s(2.0 * std::numbers::pi * n); }, n_lo, n_hi);
  const double sigma2 = s.integral(2.0 * std::numbers::pi * n_lo, 2.0 * std::numbers::pi * n_hi);
  EXPECT_NEAR(per_cycle, sigma2, 1e-9 * sigma2);
  // And the trap itself is large: integrating S(Omega) over n instead differs by 2 pi.
  const double wrong =
      simpson_log([&](double n) { return s(2.0 * std::numbers::pi * n); }, n_lo, n_hi);
  EXPECT_NEAR(sigma2 / wrong, 2.0 * std::numbers::pi, 1e-6);
}

TEST(RoughnessSpectrum, UnknownNamesAreRejected) {
  using test::expect_invalid_argument;
  expect_invalid_argument([] { RoughnessSpectrum::from_name("FRA7"); },
                          "unknown roughness spectrum 'FRA7'; use FRA1 .. FRA6 or ISO3095");
  expect_invalid_argument([] { RoughnessSpectrum::from_name("iso3095"); },
                          "unknown roughness spectrum 'iso3095'; use FRA1 .. FRA6 or ISO3095");
  expect_invalid_argument([] { RoughnessSpectrum::fra(0); },
                          "FRA track class must be 1 .. 6, got 0");
  EXPECT_EQ(RoughnessSpectrum::from_name("FRA6").name(), "FRA6");
  EXPECT_EQ(RoughnessSpectrum::from_name("ISO3095").name(), "ISO3095");
}

}  // namespace
}  // namespace rumble
