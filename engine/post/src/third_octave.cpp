#include "post/third_octave.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace rumble::post {
namespace {

// IEC 61260-1 preferred labels of the bands n = 0 .. 9 (1 Hz to 8 Hz); other decades scale.
constexpr const char* kNominal[10] = {"1", "1.25", "1.6", "2", "2.5", "3.15", "4", "5", "6.3", "8"};

std::string nominal_label(int n) {
  const int decade = n >= 0 ? n / 10 : -((-n + 9) / 10);  // floor(n / 10)
  const int step = n - 10 * decade;
  // Shift the decimal point of the 1..8 label by `decade` places, as text (no rounding noise).
  std::string digits = kNominal[step];
  std::string::size_type dot = digits.find('.');
  std::string mantissa =
      dot == std::string::npos ? digits : digits.substr(0, dot) + digits.substr(dot + 1);
  int point = static_cast<int>(dot == std::string::npos ? digits.size() : dot) + decade;
  while (point <= 0) {
    mantissa.insert(0, "0");
    ++point;
  }
  while (point > static_cast<int>(mantissa.size())) mantissa += '0';
  std::string out = mantissa.substr(0, static_cast<std::size_t>(point));
  std::string frac = mantissa.substr(static_cast<std::size_t>(point));
  while (!frac.empty() && frac.back() == '0') frac.pop_back();
  if (!frac.empty()) out += "." + frac;
  return out;
}

}  // namespace

ThirdOctaveBand third_octave_band(int n) {
  ThirdOctaveBand b;
  b.index = n;
  b.centre = std::pow(10.0, n / 10.0);
  b.lower = b.centre * std::pow(10.0, -1.0 / 20.0);
  b.upper = b.centre * std::pow(10.0, 1.0 / 20.0);
  b.nominal = nominal_label(n);
  return b;
}

std::vector<ThirdOctaveBand> third_octave_bands(double f_lo, double f_hi) {
  if (!(f_lo > 0.0) || !(f_hi >= f_lo))
    throw std::invalid_argument("third_octave_bands: the range [" + std::to_string(f_lo) + ", " +
                                std::to_string(f_hi) + "] Hz is empty or not > 0");
  std::vector<ThirdOctaveBand> out;
  // The ends are nominal centres: a band is in when its nominal frequency is, so n may pass
  // 10 log10(f) by kNominalSlack (the nominal values round the exact centres by up to 2.4 %: the
  // "250 Hz" band's centre is 251.19 Hz, 10 log10 of which is 24.0, of 250 Hz 23.98).
  constexpr double kNominalSlack = 0.15;  // in n, 10 log10(1.035)
  const int first = static_cast<int>(std::ceil(10.0 * std::log10(f_lo) - kNominalSlack));
  const int last = static_cast<int>(std::floor(10.0 * std::log10(f_hi) + kNominalSlack));
  for (int n = first; n <= last; ++n) out.push_back(third_octave_band(n));
  return out;
}

std::vector<ThirdOctaveBand> resolved_bands(const std::vector<ThirdOctaveBand>& bands,
                                            std::size_t n, double dt) {
  std::vector<ThirdOctaveBand> out;
  const double df = 1.0 / (static_cast<double>(n) * dt);
  const double nyquist = 0.5 / dt;
  for (const ThirdOctaveBand& b : bands)
    if (b.upper <= nyquist && b.upper - b.lower >= df) out.push_back(b);
  return out;
}

double level_db(double rms, double v_ref) {
  if (!(v_ref > 0.0))
    throw std::invalid_argument("level_db: reference velocity " + std::to_string(v_ref) +
                                " m/s is not > 0 (1e-9 m/s, ISO 1683; 2.54e-8 m/s for VdB)");
  if (rms == 0.0) return -std::numeric_limits<double>::infinity();
  return 20.0 * std::log10(rms / v_ref);
}

std::vector<BandLevel> band_levels(const Spectrum& power, const std::vector<ThirdOctaveBand>& bands,
                                   double v_ref) {
  std::vector<BandLevel> out;
  out.reserve(bands.size());
  for (const ThirdOctaveBand& b : bands) {
    double mean_square = 0.0;
    for (std::size_t k = 0; k < power.values.size(); ++k) {
      const double f = power.frequency(k);
      if (f >= b.lower && f < b.upper) mean_square += power.values[k];
    }
    const double rms = std::sqrt(mean_square);
    out.push_back({b, rms, level_db(rms, v_ref)});
  }
  return out;
}

}  // namespace rumble::post
