#include "track/soil_condensation.hpp"

#include "core/errors.hpp"

namespace rumble {

SoilCondensation::SoilCondensation(std::unique_ptr<IntegratedSoil> soil,
                                   const TrackStructure& structure)
    : soil_(std::move(soil)),
      n_dof_(structure.dof_count()),
      k_b_(structure.config().ballast_k),
      c_b_(structure.config().ballast_c) {
  const std::size_t n = structure.sleeper_count();
  for (std::size_t i = 0; i < n; ++i) sleeper_dof_.push_back(structure.sleeper_dof(i));
  if (soil_->footprint_count() != n) {
    throw RunError("integrated soil: its input matrix B has " +
                   std::to_string(soil_->footprint_count()) + " columns, the track has " +
                   std::to_string(n) + " footprints");
  }
  const auto ni = static_cast<Eigen::Index>(n);
  for (Eigen::VectorXd* v : {&u0_, &p_, &q_, &t_, &force_, &s_, &ws_}) v->setZero(ni);
}

void SoilCondensation::factorize(const Newmark& newmark, double h,
                                 const BandedSymmetric& a_factor) {
  const std::size_t n = sleeper_dof_.size();
  const auto ni = static_cast<Eigen::Index>(n);
  const auto nt = static_cast<Eigen::Index>(n_dof_);
  soil_->factorize(newmark, h);
  const Eigen::MatrixXd& G = soil_->step_receptance();
  kappa_ = 2.0 * (k_b_ + newmark.c_v(h) * c_b_);
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(ni, ni);
  // I + kappa G is positive definite (G is): LU without pivoting trouble.
  p_matrix_ = (identity + kappa_ * G).partialPivLu().solve(identity);
  gp_ = G * p_matrix_;
  w_ = 0.5 * kappa_ * kappa_ * gp_;
  y_.setZero(nt, ni);
  for (std::size_t j = 0; j < n; ++j) {
    y_(static_cast<Eigen::Index>(sleeper_dof_[j]), static_cast<Eigen::Index>(j)) = 1.0;
    a_factor.solve(y_.col(static_cast<Eigen::Index>(j)).data());
  }
  Eigen::MatrixXd q(ni, ni);
  for (std::size_t i = 0; i < n; ++i)
    q.row(static_cast<Eigen::Index>(i)) = y_.row(static_cast<Eigen::Index>(sleeper_dof_[i]));
  woodbury_ = (identity - w_ * q).partialPivLu().solve(w_);
}

void SoilCondensation::subtract_coupling(const double* x, double* y) const {
  for (std::size_t i = 0; i < sleeper_dof_.size(); ++i)
    s_[static_cast<Eigen::Index>(i)] = x[sleeper_dof_[i]];
  ws_.noalias() = w_ * s_;
  for (std::size_t i = 0; i < sleeper_dof_.size(); ++i)
    y[sleeper_dof_[i]] -= ws_[static_cast<Eigen::Index>(i)];
}

void SoilCondensation::correct_solve(double* y) const {
  for (std::size_t i = 0; i < sleeper_dof_.size(); ++i)
    s_[static_cast<Eigen::Index>(i)] = y[sleeper_dof_[i]];
  ws_.noalias() = woodbury_ * s_;
  Eigen::Map<Eigen::VectorXd>(y, y_.rows()).noalias() += y_ * ws_;
}

void SoilCondensation::predict(const Newmark& newmark, double h, const Eigen::VectorXd& pv_track,
                               double* rhs) {
  soil_->predict(newmark, h, u0_, p_);
  // The footprints sit at B^T x plus the soil's static offset d (IntegratedSoil::start_static):
  // the ballast's springs see it, its dashpots (velocities) do not.
  for (std::size_t i = 0; i < sleeper_dof_.size(); ++i) {
    const auto ii = static_cast<Eigen::Index>(i);
    const double d = soil_->static_offset(i);
    q_[ii] = -2.0 * c_b_ * (pv_track[static_cast<Eigen::Index>(sleeper_dof_[i])] - p_[ii]) -
             2.0 * k_b_ * d;
  }
  t_ = q_ - kappa_ * u0_;
  force_.noalias() = gp_ * t_;  // work space here; the forces come in correct()
  for (std::size_t i = 0; i < sleeper_dof_.size(); ++i) {
    const auto ii = static_cast<Eigen::Index>(i);
    rhs[sleeper_dof_[i]] +=
        0.5 * kappa_ * (u0_[ii] + force_[ii]) - c_b_ * p_[ii] + k_b_ * soil_->static_offset(i);
  }
}

void SoilCondensation::correct(const Newmark& newmark, double h, const Eigen::VectorXd& x) {
  for (std::size_t i = 0; i < sleeper_dof_.size(); ++i) {
    const auto ii = static_cast<Eigen::Index>(i);
    t_[ii] = kappa_ * (x[static_cast<Eigen::Index>(sleeper_dof_[i])] - u0_[ii]) + q_[ii];
  }
  force_.noalias() = p_matrix_ * t_;
  soil_->correct(newmark, h, force_);
}

}  // namespace rumble
