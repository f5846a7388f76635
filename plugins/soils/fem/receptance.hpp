// The footprint receptance of the FEM soil, H(f) = B^T (K + S + i w C - w^2 M)^-1 B [m/N]
// (e^{+i w t}: u = H F; C = a0 M + a1 K + D; with op's Maxwell mechanisms K (1 + i w a1) becomes
// K times their complex modulus; with a matched layer, its stretching at w), the same quantity the
// reduced soils give, so that `rumble soil-frf` overlays them and `rumble calibrate` fits them to
// it. One complex sparse LU per frequency (UMFPACK; the pattern is analysed once), one solve per
// footprint.
#pragma once

#include <complex>
#include <memory>

#include "explicit_solver.hpp"
#include "footprint_loads.hpp"

namespace rumble::fem {

class Receptance {
 public:
  Receptance(const ExplicitSolver& op, const FootprintWeights& weights, double a0, double a1);
  ~Receptance();
  Receptance(const Receptance&) = delete;
  Receptance& operator=(const Receptance&) = delete;

  /// H(f), n x n column-major (n footprints). Throws std::runtime_error when the LU fails.
  void at(double f_hz, std::complex<double>* H);

 private:
  struct Lu;
  const ExplicitSolver& op_;
  const FootprintWeights& weights_;
  double a0_, a1_;
  std::unique_ptr<Lu> lu_;
};

}  // namespace rumble::fem
