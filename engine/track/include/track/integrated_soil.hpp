// A linear soil integrated with the vehicle/track as one system: the monolithic reference
// (decision 0008). The soil's own equations, from its linear matrices (abi.h rumble_matrix),
//   M x'' + C x' + K x = B F,   u = B^T x,  v = B^T x'   (F: whole-sleeper footprint forces [N])
// are stepped with the track's Newmark at the track's micro-step, solved together with the track
// in each micro-step. For one step size the soil is linear, so its footprint motion at the step's
// end is affine in the footprint forces at the step's end:
//   u = u0 + G F,   v = c_v u - p,   G = B^T A^-1 B,  A = K + c_v C + c_a M,
// u0 the motion under no new force (from the soil's state) and p = B^T pv its velocity predictor.
// The track condenses the soil onto its sleepers with G (TrackParticipant, "integrated soil").
//
// Storage is banded, in the soil's own DOF order (tridiagonal for the lumped soils) or in a
// reverse Cuthill-McKee order where that is narrower (a FEM mesh); the state x is held in that
// order. A soil whose band would not fit (a 3D mesh: a band of 2000 on 4.5e4 DOFs) is held
// sparse instead and factored by a sparse Cholesky (Eigen's simplicial LL^T, fill-reducing
// order), up to kMaxSparseDofs; beyond that it is refused with a message.
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cstddef>
#include <rumble/newmark.hpp>
#include <string>

#include "track/banded_matrix.hpp"

namespace rumble {

class IntegratedSoil {
 public:
  /// M, C, K: n_x x n_x (symmetric), B: n_x x n_footprints. `name` for messages. Throws
  /// RunError for matrices of the wrong shape, not symmetric, too wide a band, or a singular K.
  IntegratedSoil(const std::string& name, const Eigen::SparseMatrix<double>& M,
                 const Eigen::SparseMatrix<double>& C, const Eigen::SparseMatrix<double>& K,
                 const Eigen::SparseMatrix<double>& B, double max_band_storage = kMaxBandStorage);

  std::size_t dof_count() const { return n_x_; }
  /// Half bandwidth of the matrices (after reordering where that narrowed it).
  std::size_t half_bandwidth() const { return band_; }
  /// True when held sparse (the band would not fit in max_band_storage).
  bool sparse() const { return sparse_; }
  std::size_t footprint_count() const { return n_f_; }
  /// Band storage above which a soil is held sparse [doubles]: 4e7 (320 MB for each of the three
  /// matrices and the factor).
  static constexpr double kMaxBandStorage = 4e7;
  /// DOFs above which a soil that is held sparse is refused: a 3D mesh's Cholesky factor grows
  /// about as n^(4/3) (3e5 DOFs: about 2 GB), and each micro-step solves with it twice.
  static constexpr double kMaxSparseDofs = 3e5;

  /// Static footprint displacements u = B^T K^-1 B F [m] under footprint forces F [N].
  void static_displacement(const double* force, double* u);
  /// Rest under static footprint forces F [N]: x = K^-1 B F, x' = x'' = 0. With `held` (the
  /// soil's own static footprint displacements [m]) the footprints report held + B^T (x - K^-1
  /// B F) from then on: a soil's statics may hold more than its matrices (a FEM soil's static
  /// far field, abi.h linear_matrix), which carry the motion about its static state.
  void start_static(const double* force, const double* held = nullptr);
  /// held - B^T K^-1 B F of the last start_static [m] (0 without `held`).
  double static_offset(std::size_t i) const { return offset_[static_cast<Eigen::Index>(i)]; }

  /// For step size h: factors A and forms G [m/N] (n_footprints x n_footprints, symmetric).
  void factorize(const Newmark& newmark, double h);
  const Eigen::MatrixXd& step_receptance() const { return G_; }

  /// Start of a micro-step: the predictors and the motion under no new force; u0 [m] (B^T x:
  /// without the static offset, which the caller adds where positions count), p [m/s].
  void predict(const Newmark& newmark, double h, Eigen::VectorXd& u0, Eigen::VectorXd& p);
  /// End of the micro-step under footprint forces F [N]: the soil's new state.
  void correct(const Newmark& newmark, double h, const Eigen::VectorXd& force);
  /// Footprint motion at the current state [m, m/s].
  double footprint_u(std::size_t i) const;
  double footprint_v(std::size_t i) const;

  /// Checkpointing: x, x', x'' (3 n_x values).
  std::size_t state_size() const { return 3 * n_x_; }
  double* save_state(double* buffer) const;
  const double* restore_state(const double* buffer);

 private:
  /// x = K^-1 x, x = A^-1 x (A = K + c_v C + c_a M of the last factorize), in place.
  void solve_static(Eigen::VectorXd& x) const;
  void solve_dynamic(Eigen::VectorXd& x) const;
  /// y = M a + C v.
  void inertia_and_damping(const Eigen::VectorXd& a, const Eigen::VectorXd& v,
                           Eigen::VectorXd& y) const;
  /// y = B^T x (n_footprints values) for a soil vector x.
  double footprint_dot(std::size_t i, const Eigen::VectorXd& x) const;
  void add_input(const double* force, Eigen::VectorXd& y) const;  // y += B F

  std::size_t n_x_ = 0, n_f_ = 0, band_ = 0;
  bool sparse_ = false;
  BandedSymmetric mass_, damping_, stiffness_;  // banded storage
  BandedSymmetric static_factor_;               // K, factored
  BandedSymmetric dynamic_;                     // A = K + c_v C + c_a M, factored
  Eigen::SparseMatrix<double> sparse_mass_, sparse_damping_, sparse_stiffness_;  // sparse storage
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> sparse_static_, sparse_dynamic_;
  mutable Eigen::VectorXd solved_;     // the sparse solves' result
  Eigen::SparseMatrix<double> input_;  // B (column i: footprint i)
  double h_factored_ = -1.0;
  Eigen::MatrixXd G_;

  Eigen::VectorXd x_, v_, a_;                     // state
  Eigen::VectorXd offset_;                        // start_static's, per footprint [m]
  Eigen::VectorXd pa_, pv_, rhs_, free_, x_old_;  // per-step work space
};

}  // namespace rumble
