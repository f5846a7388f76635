// The machinery shared by the reduced soils (winkler, clm), written once: per footprint i a mass
// m_i on a spring k_i and a dashpot c_i to the fixed ground, and between neighbours i, i+1 a
// spring k_c and a dashpot c_c (zero for Winkler):
//   M u'' + C u' + K u = F,   M = diag(m),   K, C tridiagonal,   u, F down + (abi.h).
// Time: Newmark average acceleration (rumble/newmark.hpp) in equal sub-steps of at most the
// sub-step inside each macro step, the force waveform evaluated at every sub-step; with m = 0 it
// is the trapezoidal rule for C u' + K u = F. Frequency: the exact receptance
// H(f) = (K - w^2 M + i w C)^-1. Both use TridiagonalLu, factored once per sub-step size or
// frequency. accept_layout() sizes everything; advance() allocates nothing. docs/soils.md.
#pragma once

#include <Eigen/Core>
#include <complex>
#include <cstddef>
#include <rumble/newmark.hpp>
#include <rumble/plugin.hpp>
#include <string>
#include <vector>

#include "tridiagonal_lu.hpp"
#include "wave_speeds.hpp"

namespace rumble::soils {

/// A model's lumped parameters for one layout.
struct LumpedParameters {
  Eigen::VectorXd mass;             // m_i [kg], >= 0
  Eigen::VectorXd stiffness;        // k_i [N/m], > 0
  Eigen::VectorXd damping;          // c_i [N s/m], >= 0
  double coupling_stiffness = 0.0;  // k_c [N/m] between neighbours, >= 0
  double coupling_damping = 0.0;    // c_c [N s/m] between neighbours, >= 0
};

class LumpedSoil : public rumble::Soil {
 public:
  void accept_layout(const std::vector<Footprint>& footprints) final;
  void initialize(double t0, const double* static_force, double* static_u) final;
  void advance(double t, double H, const Waveform& force) final;
  void motion(double* u, double* v) const final;
  bool frequency_response(double f_hz, std::complex<double>* receptance) final;
  /// M = diag(m), C and K the tridiagonal chains above, B = I (the footprint DOFs are the soil's).
  void linear_matrix(rumble_matrix which, CscMatrix& out) final;
  /// The slowest shear and Rayleigh speeds of the soil profile the model was derived from;
  /// 0 (unknown) for a model given by its springs and dashpots.
  void wave_speeds(double& c_s_min, double& c_r_min) const final {
    c_s_min = slowest_.shear;
    c_r_min = slowest_.rayleigh;
  }
  /// The state is u and v: a is recomputed from them and the waveform at every advance.
  std::size_t state_size() const final { return 2 * static_cast<std::size_t>(n_); }
  void save_state(double* buffer) const final;
  void restore_state(const double* buffer) final;

 protected:
  /// type_name prefixes every message; max_step [s] bounds the sub-step (0: automatic).
  LumpedSoil(const char* type_name, double max_step) : type_(type_name), max_step_(max_step) {}

  /// The model's parameters for this layout, or std::invalid_argument when the model cannot
  /// accept it. Vectors of size footprints.size().
  virtual LumpedParameters parameters(const std::vector<Footprint>& footprints) const = 0;

  const std::string& type_name() const { return type_; }
  /// A model derived from a soil profile records its slowest wave speeds (wave_speeds.hpp).
  void set_slowest_wave_speeds(const WaveSpeeds& s) { slowest_ = s; }

 private:
  using VectorXcd = Eigen::VectorXcd;

  void check(const LumpedParameters& p) const;
  double automatic_sub_step() const;
  bool coupled() const { return p_.coupling_stiffness > 0.0 || p_.coupling_damping > 0.0; }
  double neighbours(Eigen::Index i) const { return (i > 0 ? 1.0 : 0.0) + (i + 1 < n_ ? 1.0 : 0.0); }
  /// diag and off of wk K + wc C + wm M (T = double, or complex for the receptance).
  template <class T>
  void assemble(T wk, T wc, T wm, Eigen::Matrix<T, Eigen::Dynamic, 1>& diag,
                Eigen::Matrix<T, Eigen::Dynamic, 1>& off) const;
  /// diag(diagonal) + coupling L (L the chain's Laplacian) as CSC, zeros left out.
  void chain_csc(const Eigen::VectorXd& diagonal, double coupling, CscMatrix& out) const;
  /// Row i of (diag(diagonal) + coupling L) x, L the chain's Laplacian: K x or C x.
  double chain_row(const Eigen::VectorXd& diagonal, double coupling, const Eigen::VectorXd& x,
                   Eigen::Index i) const;
  void consistent_start(const Waveform& force, double H);
  void require_layout(const char* call) const;

  std::string type_;
  WaveSpeeds slowest_;     // m/s; zeros: unknown (direct parameters)
  double max_step_;        // s, user bound (0: automatic)
  double sub_step_ = 0.0;  // s, the bound in force for this layout
  Eigen::Index n_ = 0;
  LumpedParameters p_;
  bool any_massless_ = false, all_massless_ = false;

  Newmark newmark_;                                     // average acceleration
  Eigen::VectorXd u_, v_, a_;                           // state [m, m/s, m/s^2]
  Eigen::VectorXd pa_, pv_, rhs_, x_old_, diag_, off_;  // scratch
  TridiagonalLu<double> stiffness_lu_, damping_lu_, step_lu_;
  double factored_step_ = -1.0;  // s, the sub-step step_lu_ holds
  VectorXcd frf_diag_, frf_off_, frf_column_;
  TridiagonalLu<std::complex<double>> frf_lu_;
};

}  // namespace rumble::soils
