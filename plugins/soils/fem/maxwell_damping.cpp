#include "maxwell_damping.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rumble::fem {

MaxwellDamping MaxwellDamping::fit(double ratio, double f_low, double f_high, int mechanisms) {
  if (mechanisms < 1 || mechanisms > kMaxMechanisms || !(f_low > 0.0) || !(f_high > f_low) ||
      !(ratio >= 0.0))
    throw std::invalid_argument(
        "MaxwellDamping::fit: needs 1 to 8 mechanisms and 0 < f_low < f_high");
  const auto log_spaced = [&](int count, int k) {
    const double share = count == 1 ? 0.5 : static_cast<double>(k) / (count - 1);
    return 2.0 * std::numbers::pi * f_low * std::pow(f_high / f_low, share);
  };
  MaxwellDamping d;
  for (int l = 0; l < mechanisms; ++l) d.rates.push_back(log_spaced(mechanisms, l));
  // Im(modulus) = 2 ratio Re(modulus) at each sample frequency is linear in the weights:
  //   sum_l c_l (w omega_l - 2 ratio w^2) / (omega_l^2 + w^2) = 2 ratio.
  const int samples = 4 * mechanisms;
  Eigen::MatrixXd a(samples, mechanisms);
  const Eigen::VectorXd b = Eigen::VectorXd::Constant(samples, 2.0 * ratio);
  for (int k = 0; k < samples; ++k) {
    const double w = log_spaced(samples, k);
    for (int l = 0; l < mechanisms; ++l) {
      const double r = d.rates[l];
      a(k, l) = (w * r - 2.0 * ratio * w * w) / (r * r + w * w);
    }
  }
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(b);
  d.weights.assign(c.data(), c.data() + c.size());
  return d;
}

std::complex<double> MaxwellDamping::modulus(double omega) const {
  std::complex<double> m = 1.0;
  const std::complex<double> iw(0.0, omega);
  for (int l = 0; l < mechanisms(); ++l) m += weights[l] * iw / (rates[l] + iw);
  return m;
}

double MaxwellDamping::ratio_at(double omega) const {
  const std::complex<double> m = modulus(omega);
  return m.imag() / (2.0 * m.real());
}

double MaxwellDamping::band_error(double ratio, double f_low, double f_high) const {
  double error = 0.0;
  constexpr int kSamples = 64;
  for (int k = 0; k < kSamples; ++k) {
    const double f = f_low * std::pow(f_high / f_low, static_cast<double>(k) / (kSamples - 1));
    error = std::max(error, std::abs(ratio_at(2.0 * std::numbers::pi * f) / ratio - 1.0));
  }
  return error;
}

bool MaxwellDamping::dissipative() const {
  return std::all_of(weights.begin(), weights.end(), [](double c) { return c > 0.0; });
}

double MaxwellDamping::unrelaxed() const {
  double s = 1.0;
  for (const double c : weights) s += c;
  return s;
}

}  // namespace rumble::fem
