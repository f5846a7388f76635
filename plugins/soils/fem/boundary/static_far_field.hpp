// The half-space's static field of the footprints' loads on the truncation surface
// (docs/fem-soil.md section 3.2): Boussinesq's point load integrated over each footprint's
// uniform pressure. It fits the boundary springs (absorbing_boundary.cpp) and gives the
// statics the traction that the soil beyond the surface exerts, so that the truncated soil's
// static state is the half-space's under any footprint load.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <complex>
#include <cstdint>
#include <rumble/plugin.hpp>
#include <vector>

#include "boundary/absorbing_boundary.hpp"
#include "fem_settings.hpp"
#include "mesh/tet_mesh.hpp"

namespace rumble::fem {

/// A point of a footprint's load [m] and its share of the force [-].
struct LoadPoint {
  Eigen::Vector3d at;
  double share = 0.0;
};

/// A footprint's uniform pressure as 2 x 4 Gauss-Legendre point loads (4 along its length, the
/// sleeper's long side) whose shares add up to `share`. The nearest boundary node is a fifth of
/// the radius away, where the rule is exact to about 1e-4.
void add_load_points(const Footprint& footprint, double share, std::vector<LoadPoint>& points);

/// Displacement [m] and the traction -sigma n [Pa] that a spring at x (outward normal n) must
/// give to hold the half-space's field of the loads there (shares in N), for G [Pa] and nu.
struct HeldField {
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();
  Eigen::Vector3d spring_force = Eigen::Vector3d::Zero();
};
HeldField half_space_field(const Eigen::Vector3d& x, const Eigen::Vector3d& n,
                           const std::vector<LoadPoint>& loads, double G, double nu);

/// Whether the statics take the far field: half-space springs on a homogeneous soil (the
/// closed form is the half-space's; a layered profile keeps the springs alone).
bool static_far_field_applies(const FemSettings& settings);

/// Per footprint j and boundary node the load g_j = S phi_j - A (-sigma_j n) [N per N of F_j]:
/// with it the boundary's force -S u + sum_j F_j g_j is the half-space's traction whenever u is
/// the half-space's field phi of the loads, so (K + S) u = B F + G F holds it exactly.
class StaticFarField {
 public:
  StaticFarField(const TetMesh& mesh, const FemSettings& settings,
                 const std::vector<Footprint>& footprints,
                 const std::vector<BoundaryNode>& boundary);
  /// f += G F (F: one force per footprint [N]) at the boundary nodes' DOFs.
  void add(const double* F, Eigen::VectorXd& f, unsigned threads = 1) const;
  /// The boundary's traction moving from G before to G now (one force per footprint [N]), at
  /// the boundary nodes' DOFs, overwriting them, nothing elsewhere: f = G now, jump = G now -
  /// G before. One pass over G per call (each macro step calls it): G before is the last call's
  /// G now, formed again only where `before` is not that call's `now` (a restored state).
  /// Allocates nothing after its first call.
  void follow(const double* before, const double* now, Eigen::VectorXd& f, Eigen::VectorXd& jump,
              unsigned threads);
  /// f = g_j F_j at the boundary nodes' DOFs, overwriting them (one footprint's force alone).
  void set_column(std::size_t j, double F_j, Eigen::VectorXd& f) const;
  /// rhs(:, j) += factor g_j (the receptance's right-hand sides, one column per footprint).
  void add_columns(std::complex<double> factor, Eigen::MatrixXcd& rhs) const;
  const std::vector<std::int32_t>& nodes() const { return nodes_; }
  /// g_j per footprint j (columns), 3 rows per node of nodes().
  const Eigen::MatrixXd& loads() const { return loads_; }
  /// Mean distance [m] of the boundary nodes from the footprints' centre.
  double mean_distance() const { return mean_distance_; }
  /// Bytes held (G, and follow()'s two products once it runs).
  double bytes() const { return 8.0 * static_cast<double>(loads_.size() + 2 * loads_.rows()); }

 private:
  /// g = G F, the rows split over `threads`, each row summed in footprint order: the same bits
  /// on any number of threads, and on a rank's rows as on one process's.
  void product(const double* F, Eigen::VectorXd& g, unsigned threads) const;

  std::vector<std::int32_t> nodes_;  // the boundary nodes, in the rows' order
  Eigen::MatrixXd loads_;            // 3 per node x footprints [N/N]
  double mean_distance_ = 0.0;       // m
  mutable Eigen::VectorXd g_;        // scratch: G F
  // follow()'s last G now, and the forces it was formed from [N]
  Eigen::VectorXd held_g_;
  std::vector<double> held_;
};

/// How the far field's traction follows the footprint forces in time (docs/fem-soil.md §3.2):
/// the boundary holds G dF_lag, dF_lag the forces' change from the static state lagged by tau,
/// the time shear waves take to reach the truncation surface:
///   d(dF_lag)/dt = (dF - dF_lag) / tau,
/// advanced exactly over each macro step with dF held at the step's middle. A load held long
/// enough settles to the half-space's static state, as the statics do.
struct FarFieldLag {
  double tau = 0.0;            // s
  std::vector<double> lagged;  // [N] per footprint: the change the boundary holds now

  /// Over a macro step of H [s] towards `change` [N per footprint].
  void advance(const std::vector<double>& change, double H) {
    const double keep = std::exp(-H / tau);
    for (std::size_t j = 0; j < lagged.size(); ++j)
      lagged[j] = change[j] + (lagged[j] - change[j]) * keep;
  }
  /// The lag's frequency response at w [rad/s] (e^{+i w t}): 1 / (1 + i w tau).
  std::complex<double> at(double w) const { return 1.0 / std::complex<double>(1.0, w * tau); }
};

}  // namespace rumble::fem
