// The integrated soil (track/integrated_soil.hpp) condensed onto the track's sleepers, so that
// the track's Newton iteration solves track and soil as one system without refactoring its banded
// matrix (decision 0008). Per rail, ballast k_b [N/m], c_b [N s/m]; whole-sleeper footprint force
//   F = 2 [k_b (s - u) + c_b (s' - v)] = kappa (s - u) + q,
//   kappa = 2 (k_b + c_v c_b),  q = -2 c_b (pv_s - p)   (s' = c_v s - pv_s, v = c_v u - p),
// and the soil's end-of-step motion u = u0 + G F give F = P [kappa (s - u0) + q], P = (I + kappa
// G)^-1. The ballast's load on the sleepers, k_b u + c_b v, is then
//   b0 + W s,   W = (kappa^2 / 2) G P,   b0 = (kappa / 2) [u0 + G P (q - kappa u0)] - c_b p,
// so the track's matrix becomes A - S W S^T (S: the sleeper DOFs), rank n_sleepers, solved by
// Woodbury with Y = A^-1 S:  (A - S W S^T)^-1 r = y + Y (I - W Q)^-1 W S^T y,  y = A^-1 r,
// Q = S^T Y. Everything of size n_sleepers^2 or n_dof n_sleepers is formed once per step size.
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <memory>
#include <rumble/newmark.hpp>
#include <vector>

#include "track/banded_matrix.hpp"
#include "track/integrated_soil.hpp"
#include "track/track_structure.hpp"

namespace rumble {

class SoilCondensation {
 public:
  SoilCondensation(std::unique_ptr<IntegratedSoil> soil, const TrackStructure& structure);

  IntegratedSoil& soil() { return *soil_; }
  const IntegratedSoil& soil() const { return *soil_; }

  /// For step size h, after the track's A = K + c_v C + c_a M is factored (`a_factor`).
  void factorize(const Newmark& newmark, double h, const BandedSymmetric& a_factor);
  /// y -= S W S^T x: with A x in y, y becomes the condensed system's A x.
  void subtract_coupling(const double* x, double* y) const;
  /// With A^-1 r in y, y becomes the condensed system's inverse applied to r.
  void correct_solve(double* y) const;

  /// Start of a micro-step (after the track's predictors pv_track): the soil's predictors, and
  /// b0 added to the sleeper rows of the track's right-hand side `rhs`.
  void predict(const Newmark& newmark, double h, const Eigen::VectorXd& pv_track, double* rhs);
  /// End of a micro-step, from the track's converged displacements x: the footprint forces and
  /// the soil's new state.
  void correct(const Newmark& newmark, double h, const Eigen::VectorXd& x);

 private:
  std::unique_ptr<IntegratedSoil> soil_;
  std::vector<std::size_t> sleeper_dof_;  // S: the track DOF of each sleeper
  std::size_t n_dof_ = 0;                 // track DOFs
  double k_b_ = 0.0, c_b_ = 0.0;          // ballast per rail seat [N/m, N s/m]
  double kappa_ = 0.0;                    // N/m, whole sleeper
  Eigen::MatrixXd p_matrix_;              // P = (I + kappa G)^-1
  Eigen::MatrixXd gp_;                    // G P [m/N]
  Eigen::MatrixXd w_;                     // W [N/m]
  Eigen::MatrixXd y_;                     // A^-1 S, n_dof x n_sleepers
  Eigen::MatrixXd woodbury_;              // (I - W Q)^-1 W
  // Per-step work space (n_sleepers values).
  Eigen::VectorXd u0_, p_, q_, t_, force_;
  mutable Eigen::VectorXd s_, ws_;
};

}  // namespace rumble
