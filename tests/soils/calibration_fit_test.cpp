// Calibration as `rumble calibrate` will do it: a least-squares fit of the CLM's five parameters
// on a target receptance, using nothing but the plugin's frequency_response through the ABI.
// The target is the CLM itself with known parameters, so the fit must recover them.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <nlohmann/json.hpp>

#include "soil_harness.hpp"

namespace rumble::test {
namespace {

constexpr Eigen::Index kFootprints = 21, kCentre = 10, kTerms = 3;  // H_00, H_01, H_02
constexpr int kFrequencies = 20;                                    // 2 to 100 Hz, log-spaced

using Parameters = Eigen::Matrix<double, 5, 1>;  // m_f, k_f, c_f, k_c, c_c

double frequency(int j) {
  return 2.0 * std::pow(50.0, j / (kFrequencies - 1.0));
}

/// The receptances of the centre footprint (driving point and two neighbours) at the fit
/// frequencies, stacked as real and imaginary parts.
VectorXd receptances(const Parameters& p) {
  const nlohmann::json params = {
      {"m_f", p[0]}, {"k_f", p[1]}, {"c_f", p[2]}, {"k_c", p[3]}, {"c_c", p[4]}};
  TestSoil soil("clm", params.dump());
  soil.accept_layout(sleeper_row(kFootprints));
  VectorXd out(2 * kTerms * kFrequencies);
  for (int j = 0; j < kFrequencies; ++j) {
    const MatrixXcd H = soil.receptance(frequency(j));
    for (Eigen::Index t = 0; t < kTerms; ++t) {
      out[2 * (kTerms * j + t)] = H(kCentre + t, kCentre).real();
      out[2 * (kTerms * j + t) + 1] = H(kCentre + t, kCentre).imag();
    }
  }
  return out;
}

/// Levenberg-Marquardt on log-parameters, residuals relative to the target's driving point.
Parameters fit(const VectorXd& target, Parameters start) {
  VectorXd scale(target.size());
  for (int j = 0; j < kFrequencies; ++j) {
    const double h00 = std::hypot(target[2 * kTerms * j], target[2 * kTerms * j + 1]);
    scale.segment(2 * kTerms * j, 2 * kTerms).setConstant(1.0 / h00);
  }
  const auto residual = [&](const Parameters& logp) {
    return VectorXd((receptances(logp.array().exp().matrix()) - target).cwiseProduct(scale));
  };
  Parameters logp = start.array().log().matrix();
  VectorXd r = residual(logp);
  double lambda = 1e-3;
  for (int iteration = 0; iteration < 100 && r.norm() > 1e-13; ++iteration) {
    Eigen::Matrix<double, Eigen::Dynamic, 5> J(r.size(), 5);
    for (int k = 0; k < 5; ++k) {  // forward differences in log p
      Parameters q = logp;
      q[k] += 1e-7;
      J.col(k) = (residual(q) - r) / 1e-7;
    }
    const Eigen::Matrix<double, 5, 5> JtJ = J.transpose() * J;
    const Parameters g = J.transpose() * r;
    Eigen::Matrix<double, 5, 5> A = JtJ;
    A.diagonal() *= 1.0 + lambda;
    const Parameters step = -A.ldlt().solve(g);
    const VectorXd trial = residual(logp + step);
    if (trial.norm() < r.norm()) {
      logp += step;
      r = trial;
      lambda = std::max(lambda / 3.0, 1e-12);
    } else {
      lambda *= 4.0;
    }
  }
  return logp.array().exp().matrix();
}

TEST(SoilCalibrationFit, LeastSquaresRecoversKnownClmParameters) {
  // About the medium soil's calibrated chain, with a 300 kg mass.
  Parameters truth;
  truth << 300.0, 9.6e7, 1.5e5, 1.0e8, 1.6e5;
  const VectorXd target = receptances(truth);
  Parameters start;  // every parameter wrong by 40 to 100 %
  start << 1.6 * truth[0], 0.6 * truth[1], 1.5 * truth[2], 0.7 * truth[3], 2.0 * truth[4];
  const Parameters found = fit(target, start);
  // Exact data and an exact model: the optimum is the truth; the finite-difference Jacobian only
  // slows the last iterations. 1e-6 is far below any engineering need and far above round-off.
  for (int k = 0; k < 5; ++k) EXPECT_NEAR(found[k] / truth[k], 1.0, 1e-6) << "parameter " << k;
  // The check can fail: the start is far from the truth.
  EXPECT_GT((receptances(start) - target).norm(), 0.1 * target.norm());
}

}  // namespace
}  // namespace rumble::test
