#include "track_spec/unevenness_psd.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace rumble {
namespace {

// US FRA vertical profile, classes 1..6 (see the header for the source).
constexpr std::array<double, 6> kFraAvCm2 = {1.2107, 1.0181, 0.6816, 0.5376, 0.2095, 0.0339};
constexpr double kFraOmegaC = 0.8245;  // rad/m
constexpr double kFraK = 0.25;
constexpr double kCm2 = 1e-4;  // m^2 per cm^2

// ISO 3095:2013 Figure 2: one-third octave band levels [dB re 1 um], band n = 4 .. 25 with the
// centre wavelength 10^(-n/10) m (nominal 40, 31.5, 25, ..., 0.4, 0.315 cm).
constexpr int kIsoFirstBand = 4;
constexpr std::array<double, 22> kIsoLevelsDb = {17.1, 15.0, 13.0, 11.0, 9.0,   7.0,  4.9,  2.9,
                                                 0.9,  -1.1, -3.2, -5.0, -5.6,  -6.2, -6.8, -7.4,
                                                 -8.0, -8.6, -9.2, -9.8, -10.4, -11.0};
constexpr double kIsoReference = 1e-6;  // m, 0 dB

/// x - atan(x) without cancellation for small x (series to x^9, error < x^11/11).
double x_minus_atan(double x) {
  if (std::abs(x) > 1e-2) return x - std::atan(x);
  const double x2 = x * x;
  return x * x2 * (1.0 / 3.0 - x2 * (1.0 / 5.0 - x2 * (1.0 / 7.0 - x2 / 9.0)));
}

/// integral_a^b (Omega/w0)^p dOmega / w0 for 0 < a <= b, through expm1 and log1p of (b - a)/a
/// so that narrow intervals keep full precision; q = p + 1 = 0 is the logarithm.
double power_integral(double a, double b, double w0, double p) {
  const double width = std::log1p((b - a) / a);  // ln(b/a)
  const double q = p + 1.0;
  if (q == 0.0) return width;
  return std::pow(a / w0, q) * std::expm1(q * width) / q;
}

}  // namespace

RoughnessSpectrum RoughnessSpectrum::fra(int track_class) {
  if (track_class < 1 || track_class > 6) {
    throw std::invalid_argument("FRA track class must be 1 .. 6, got " +
                                std::to_string(track_class));
  }
  RoughnessSpectrum s;
  s.name_ = "FRA" + std::to_string(track_class);
  s.min_wavelength_ = 0.0;
  s.max_wavelength_ = std::numeric_limits<double>::infinity();
  s.fra_scale_ = kFraK * kFraAvCm2[static_cast<std::size_t>(track_class - 1)] * kCm2;
  s.fra_omega_c_ = kFraOmegaC;
  return s;
}

RoughnessSpectrum RoughnessSpectrum::iso3095() {
  RoughnessSpectrum s;
  s.name_ = "ISO3095";
  const double half_band = std::pow(10.0, 0.05);  // band edges at centre * 10^(+-1/20)
  const double width = half_band - 1.0 / half_band;
  const int n_last = kIsoFirstBand + static_cast<int>(kIsoLevelsDb.size()) - 1;
  s.max_wavelength_ = std::pow(10.0, -kIsoFirstBand / 10.0) * half_band;
  s.min_wavelength_ = std::pow(10.0, -n_last / 10.0) / half_band;
  // Nodes in increasing Omega: from the longest band (n = 4) to the shortest (n = 25).
  std::vector<double> band_power;  // r_i^2 [m^2]
  for (std::size_t i = 0; i < kIsoLevelsDb.size(); ++i) {
    const double lambda = std::pow(10.0, -(kIsoFirstBand + static_cast<int>(i)) / 10.0);
    const double omega = 2.0 * std::numbers::pi / lambda;
    band_power.push_back(kIsoReference * kIsoReference * std::pow(10.0, kIsoLevelsDb[i] / 10.0));
    s.omega_.push_back(omega);
    s.psd_.push_back(band_power.back() / (omega * width));
  }
  // Where the slope of the levels changes (3.15 cm, 1.6 cm) a power law through r_i^2/dOmega_i
  // misses the band's power by up to 0.16 dB. Rescale the node values until every band's
  // integral is its r_i^2 (multiplicative Jacobi sweeps; each band's integral depends mostly on
  // its own node, so the sweeps contract fast: ~10 to reach 1e-13).
  s.exponent_.resize(s.omega_.size() - 1);
  const auto update_exponents = [&s] {
    for (std::size_t i = 0; i + 1 < s.omega_.size(); ++i) {
      s.exponent_[i] =
          std::log(s.psd_[i + 1] / s.psd_[i]) / std::log(s.omega_[i + 1] / s.omega_[i]);
    }
  };
  update_exponents();
  std::vector<double> factor(s.omega_.size());
  for (int sweep = 0; sweep < 100; ++sweep) {
    double change = 0.0;
    for (std::size_t i = 0; i < s.omega_.size(); ++i) {
      const double actual = s.power_law_integral(s.omega_[i] / half_band, s.omega_[i] * half_band);
      factor[i] = band_power[i] / actual;
      change = std::max(change, std::abs(std::log(factor[i])));
    }
    if (change < 1e-13) break;
    for (std::size_t i = 0; i < s.omega_.size(); ++i) s.psd_[i] *= factor[i];
    update_exponents();
  }
  return s;
}

RoughnessSpectrum RoughnessSpectrum::from_name(const std::string& name) {
  if (name == "ISO3095") return iso3095();
  if (name.size() == 4 && name.rfind("FRA", 0) == 0 && name[3] >= '1' && name[3] <= '6')
    return fra(name[3] - '0');
  throw std::invalid_argument("unknown roughness spectrum '" + name +
                              "'; use FRA1 .. FRA6 or ISO3095");
}

double RoughnessSpectrum::operator()(double omega) const {
  if (omega_.empty()) {
    const double w2 = omega * omega, c2 = fra_omega_c_ * fra_omega_c_;
    return fra_scale_ * c2 / (w2 * (w2 + c2));
  }
  // Segment i holds omega in [omega_i, omega_i+1); the end segments continue outwards.
  const auto it = std::upper_bound(omega_.begin(), omega_.end(), omega);
  const std::size_t i = std::clamp<std::size_t>(
      static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - omega_.begin() - 1, 0)), 0,
      exponent_.size() - 1);
  return psd_[i] * std::pow(omega / omega_[i], exponent_[i]);
}

double RoughnessSpectrum::integral(double omega_lo, double omega_hi) const {
  if (!(omega_lo > 0.0) || !(omega_hi >= omega_lo)) {
    throw std::invalid_argument("RoughnessSpectrum::integral needs 0 < omega_lo <= omega_hi");
  }
  return omega_.empty() ? fra_integral(omega_lo, omega_hi) : power_law_integral(omega_lo, omega_hi);
}

double RoughnessSpectrum::fra_integral(double a, double b) const {
  // S = s c^2 / (W^2 (W^2 + c^2)) = s (1/W^2 - 1/(W^2 + c^2)), so
  // integral = s [(1/a - 1/b) - (atan(b/c) - atan(a/c))/c]. Both brackets nearly cancel for
  // narrow or short-wave intervals; with u = c (b - a)/(c^2 + a b) = tan(atan(b/c) - atan(a/c)):
  // integral = s [(b - a) c^2 / (a b (a b + c^2)) + (u - atan u)/c], each term >= 0.
  const double c = fra_omega_c_, d = b - a, ab = a * b;
  const double u = c * d / (c * c + ab);
  return fra_scale_ * (d * c * c / (ab * (ab + c * c)) + x_minus_atan(u) / c);
}

double RoughnessSpectrum::power_law_integral(double a, double b) const {
  double sum = 0.0;
  const std::size_t last = exponent_.size() - 1;
  // First segment holding a; the end segments extend to 0 and infinity.
  std::size_t i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(
      std::upper_bound(omega_.begin(), omega_.end(), a) - omega_.begin() - 1, 0));
  i = std::min(i, last);
  for (double lo = a; lo < b; ++i) {
    const double hi = i == last ? b : std::min(b, omega_[i + 1]);
    if (hi > lo) sum += psd_[i] * omega_[i] * power_integral(lo, hi, omega_[i], exponent_[i]);
    lo = hi;
    if (i == last) break;
  }
  return sum;
}

}  // namespace rumble
