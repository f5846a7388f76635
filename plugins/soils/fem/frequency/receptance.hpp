// The footprint receptance of the FEM soil, H(f) = B^T (K + S + i w C - w^2 M)^-1 (B + G L(w))
// [m/N], G L the far field's lagged traction (static_far_field.hpp; none without it)
// (e^{+i w t}: u = H F; C = a0 M + a1 K + D; with op's Maxwell mechanisms K (1 + i w a1) becomes
// K times their complex modulus; with a matched layer, its stretching at w), the same quantity the
// reduced soils give, so that `rumble soil-frf` overlays them and `rumble calibrate` fits them to
// it. One complex sparse LU per frequency (UMFPACK; the pattern is analysed once), one solve per
// footprint.
#pragma once

#include <complex>
#include <memory>

#include "boundary/static_far_field.hpp"
#include "operator/footprint_loads.hpp"
#include "time/explicit_solver.hpp"

namespace rumble::fem {

class Receptance {
 public:
  Receptance(const ExplicitSolver& op, const FootprintWeights& weights, double a0, double a1);
  ~Receptance();
  Receptance(const Receptance&) = delete;
  Receptance& operator=(const Receptance&) = delete;

  /// H(f), n x n column-major (n footprints). Throws std::runtime_error when the LU fails.
  void at(double f_hz, std::complex<double>* H);
  /// The far field's traction follows each footprint's force through `lag` (the time step's
  /// FarFieldLag, docs/fem-soil.md §3.2): the right-hand sides become B + G / (1 + i w tau), so
  /// that H(0) is the half-space's static compliance. Both must outlive this; nullptr: none.
  void set_far_field(const StaticFarField* far, const FarFieldLag* lag) {
    far_ = far;
    lag_ = lag;
  }

 private:
  struct Lu;
  // at()'s steps at the circular frequency w [rad/s]: the soil's terms into the LU's matrix (its
  // pattern K's), the matched layer's, the boundary's springs and dashpots; then its LU.
  void assemble_soil(double w);
  void add_layer(double w);
  void add_boundary(double w);
  void factorize(double f_hz);
  const StaticFarField* far_ = nullptr;
  const FarFieldLag* lag_ = nullptr;
  const ExplicitSolver& op_;
  const FootprintWeights& weights_;
  double a0_, a1_;
  std::unique_ptr<Lu> lu_;
};

}  // namespace rumble::fem
