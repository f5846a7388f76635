#include "analysis/calibrate.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "core/errors.hpp"
#include "plugin/instance.hpp"

namespace rumble {
namespace {

constexpr int kMaxIterations = 200;
constexpr double kLogStep = 1e-6;  // finite-difference step in log(parameter)

/// Residual vector: real and imaginary parts of (H - H_target) / |H_target driving point|.
Eigen::VectorXd residuals(const CalibrationProblem& p, const nlohmann::json& params) {
  SoilInstance soil(*p.model, "calibrate", params, p.scenario_dir);
  soil.accept_layout(p.layout);
  SoilFrf frf;
  if (!soil_frf(soil, p.layout.size(), p.target.frequency, p.target.receptance.size() - 1, frf)) {
    throw ConfigError("soil type '" + p.model->type_name +
                      "' offers no frequency response, so it cannot be calibrated");
  }
  const std::size_t terms = p.target.receptance.size(), nf = p.target.frequency.size();
  Eigen::VectorXd r(static_cast<Eigen::Index>(2 * terms * nf));
  Eigen::Index i = 0;
  for (std::size_t k = 0; k < terms; ++k) {
    for (std::size_t j = 0; j < nf; ++j) {
      const std::complex<double> d =
          (frf.receptance[k][j] - p.target.receptance[k][j]) / std::abs(p.target.receptance[0][j]);
      r[i++] = d.real();
      r[i++] = d.imag();
    }
  }
  return r;
}

nlohmann::json with_values(const CalibrationProblem& p, const Eigen::VectorXd& log_values) {
  nlohmann::json params = p.base_params;
  for (std::size_t k = 0; k < p.fit.size(); ++k)
    params[p.fit[k]] = std::exp(log_values[static_cast<Eigen::Index>(k)]);
  return params;
}

double rms(const Eigen::VectorXd& r) {
  return std::sqrt(r.squaredNorm() / (0.5 * static_cast<double>(r.size())));
}

}  // namespace

double receptance_misfit(const CalibrationProblem& problem, const nlohmann::json& params) {
  return rms(residuals(problem, params));
}

CalibrationResult calibrate(const CalibrationProblem& p) {
  const auto n = static_cast<Eigen::Index>(p.fit.size());
  Eigen::VectorXd x(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const std::string& name = p.fit[static_cast<std::size_t>(k)];
    if (!p.base_params.contains(name) || !p.base_params[name].is_number() ||
        !(p.base_params[name].get<double>() > 0.0)) {
      throw ConfigError("calibrate: parameter '" + name + "' of '" + p.model->type_name +
                        "' needs a positive starting value in the model's params");
    }
    x[k] = std::log(p.base_params[name].get<double>());
  }
  Eigen::VectorXd r = residuals(p, with_values(p, x));
  double cost = r.squaredNorm();
  double lambda = 1e-3;
  CalibrationResult result;
  Eigen::MatrixXd J(r.size(), n);
  for (result.iterations = 0; result.iterations < kMaxIterations; ++result.iterations) {
    for (Eigen::Index k = 0; k < n; ++k) {
      Eigen::VectorXd xp = x;
      xp[k] += kLogStep;
      J.col(k) = (residuals(p, with_values(p, xp)) - r) / kLogStep;
    }
    const Eigen::MatrixXd JtJ = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * r;
    bool improved = false;
    for (int attempt = 0; attempt < 20 && !improved; ++attempt) {
      Eigen::MatrixXd A = JtJ;
      A.diagonal() += lambda * JtJ.diagonal().cwiseMax(1e-30);
      const Eigen::VectorXd step = -A.ldlt().solve(g);
      const Eigen::VectorXd x_new = x + step.cwiseMax(-2.0).cwiseMin(2.0);  // factor e^2 at most
      const Eigen::VectorXd r_new = residuals(p, with_values(p, x_new));
      if (r_new.squaredNorm() < cost) {
        const double reduction = (cost - r_new.squaredNorm()) / cost;
        const double move = (x_new - x).cwiseAbs().maxCoeff();
        x = x_new;
        r = r_new;
        cost = r.squaredNorm();
        lambda = std::max(lambda / 3.0, 1e-12);
        improved = true;
        if (reduction < 1e-12 || move < 1e-9) result.converged = true;
      } else {
        lambda *= 4.0;
      }
    }
    if (!improved || result.converged) {
      result.converged = true;  // no descent direction left: a (local) minimum
      break;
    }
  }
  result.params = with_values(p, x);
  result.relative_rms = rms(r);
  return result;
}

}  // namespace rumble
