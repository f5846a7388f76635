// A perfectly matched layer (PML) around the box's sides and bottom: the soil beyond the physical
// box in complex stretched coordinates, so that a wave of any incidence enters it without
// reflection (in the continuum) and decays there. Unsplit displacement formulation with the
// complex-frequency-shifted stretching s_i = 1 + d_i / (alpha + i omega) (CFS-PML: alpha > 0
// gives every memory term a decay, where the classical PML's pure time integrals keep the strain
// of a passed wave for ever and grow under a static one); what it measures and costs is in
// docs/fem-soil.md §3.1. With q = 1 / (alpha + i omega), the weak form (= 0)
//   integral rho S (i omega)^2 u . w  +  integral sum_ik (S / (s_i s_k)) C_ijkm d_k u_m d_i w_j,
// S = s_x s_y s_z, becomes in time (phi = q applied: phi' = -alpha phi + input)
//   mass side:      rho (u'' + D1 u' + (D2 - alpha D1) u + (alpha^2 D1 - 2 alpha D2 + D3) phi u
//                        + (alpha^2 D2 - 2 alpha D3) phi^2 u + alpha^2 D3 phi^3 u),
//                   D1 = sum d, D2 = sum of pair products, D3 = d_x d_y d_z;
//   stiffness side: S / (s_i s_k) = s_l (i != k, l the third axis): g + d_l phi g;
//                   S / s_k^2 = s_l s_m / s_k: h + (d_l + d_m) phi h + d_l d_m phi^2 h, with
//                   h = g - d_k psi, psi' = -(alpha + d_k) psi + g (g the displacement gradient).
// The mass side is lumped per node (d taken at each tetrahedron's centroid, like the stiffness
// side): damping and springs on the diagonal, so the step stays explicit. The stiffness side is
// computed element by element on the PML's tetrahedra (linear tetrahedra: one gradient each), as
// a correction to K w, so K (the static operator, the stable step's eigenvalue iteration) stays the
// elastic one. Memory per PML tetrahedron: 54 doubles; per PML node: 9. Each filter is
// integrated by the trapezoidal rule with the exact decay (second order).
// The damping profile is d_i = d0 (distance into the layer along i / thickness)^2 with
// d0 = 3 c_p ln(1 / R) / (2 thickness), R the reflection of a normally incident P wave.
#pragma once

#include <Eigen/Core>
#include <array>
#include <complex>
#include <cstdint>
#include <functional>
#include <vector>

#include "fem_settings.hpp"
#include "mesh/pml_profile.hpp"
#include "mesh/tet_mesh.hpp"

namespace rumble::fem {

class PmlLayer {
 public:
  /// The tetrahedra whose centroid lies beyond the physical box, with their damping.
  PmlLayer(const TetMesh& mesh, const FemSettings& settings, const PmlProfile& profile);

  std::size_t tetrahedra() const { return tets_.size(); }
  /// Doubles of state the layer keeps (its memory variables), zero at rest.
  Eigen::Index memory_size() const {
    return kPerTet * tets_.size() + kPerNode * mass_terms_.size();
  }
  /// Per node: index into the layer's nodes, or -1 outside the layer.
  std::int32_t layer_node(Eigen::Index node) const { return local_[node]; }
  /// The lumped mass-side damping of a layer node [N s/m]: rho V / 4 D1 summed.
  double damping(std::int32_t local) const { return mass_terms_[local][0]; }
  /// The mass side's springs and filtered-displacement terms on layer node `local`: adds them
  /// to the force out [N] (3 components), after updating the node's filters (in memory) with
  /// its displacement w_old at the step's start and w_new at its end [m].
  void add_node_forces(std::int32_t local, const double* w_old, const double* w_new, double dt,
                       double* memory, double* out) const;

  /// After the displacement w has advanced by dt: updates the tetrahedra's memory (in
  /// memory[0, kPerTet tetrahedra())) and writes each tetrahedron's correction force
  /// (stretched minus elastic internal force, 12 per tetrahedron) into forces. Call inside an
  /// OpenMP parallel region: the tetrahedra are shared out with `omp for`.
  void update_tetrahedra(const double* w, double dt, double* memory, double* forces) const;
  /// Sum of the correction forces on layer node `local` [N] (3 components, added to out).
  void gather(std::int32_t local, const double* forces, double* out) const;

  /// The layer in the frequency domain at omega [rad/s] (e^{+i w t}): the semi-discrete system
  /// the step integrates, its filters phi = q = 1 / (alpha + i w). Hands each tetrahedron's
  /// stretched-minus-elastic stiffness to add_block(a, b, block) (mesh nodes; block(j, c) the
  /// force on a's component j per unit displacement of b's component c [N/m]), and each layer
  /// node's mass-side terms i w D1 + ... (pml.hpp's mass side, without the inertia) to
  /// add_node(node, value) [N/m], on each of its three components.
  void frequency_domain(
      double omega,
      const std::function<void(std::int32_t, std::int32_t, const Eigen::Matrix3cd&)>& add_block,
      const std::function<void(std::int32_t, std::complex<double>)>& add_node) const;
  static constexpr Eigen::Index kPerTet = 54, kPerNode = 9;

  std::size_t bytes() const;

  /// The largest damping d_i [1/s] of the layer.
  double max_damping() const { return max_damping_; }

  // On a part of a mesh split over ranks (distributed/part_pml.hpp): a layer node on the part's
  // border may have its layer tetrahedra on another rank alone, and its mass side is summed over
  // the ranks' tetrahedra.
  /// Makes each of `nodes` a layer node where it is not one (no tetrahedron here, zero terms).
  void add_nodes(const std::vector<std::int32_t>& nodes);
  /// The mass side's coefficients per layer node: of u', u, phi u, phi^2 u and phi^3 u.
  static constexpr int kMassTerms = 5;
  /// Layer node `local`'s mass-side coefficients (damping(local) is the first), to be summed.
  std::array<double, kMassTerms>& mass_terms(std::int32_t local) { return mass_terms_[local]; }
  /// The largest damping over the ranks' layers (the step's bound, kStableDampingStep).
  void set_max_damping(double d) { max_damping_ = d; }
  /// The explicit step's bound from the layer: d_max dt at most this. Measured, not derived
  /// (docs/fem-soil.md section 3.1): with alpha = 2 pi 5 Hz the discrete layer stays bounded over
  /// 2 s at d_max dt = 0.46 and grows slowly at 0.51 (structured meshes, R 1e-3 and 1e-2, 8 and
  /// 12 elements across, d_max at the outer edge); a larger alpha is more stable, alpha = 0
  /// grows at any step. 0.4 of the centroids' largest d leaves room for courant 1.
  static constexpr double kStableDampingStep = 0.4;

 private:
  struct Tet {
    std::array<std::int32_t, 4> nodes;
    Eigen::Matrix<double, 3, 4> gradient;  // shape-function gradients [1/m]
    double volume, lambda, mu;             // m^3, Pa, Pa
    Eigen::Vector3d d;                     // damping along x, y, depth [1/s]
  };
  double shift_;              // alpha [1/s]
  double max_damping_ = 0.0;  // the largest d_i of any tetrahedron [1/s]
  std::vector<Tet> tets_;
  // Per tetrahedron exp(-(alpha + d_k) dt) for k = x, y, depth, at the step decays_dt_ [s]:
  // three exp calls per tetrahedron and step were 11 % of a matched-layer run's step (perf on
  // FemPml.StaysBoundedAtItsStepAndGrowsBeyond), for values that change only with dt. Made
  // again when dt changes (update_tetrahedra).
  mutable std::vector<std::array<double, 3>> decays_;
  mutable double decays_dt_ = 0.0;
  std::vector<std::int32_t> local_;                         // per mesh node
  std::vector<std::array<double, kMassTerms>> mass_terms_;  // per layer node [SI]
  std::vector<std::int64_t> incidence_offset_;              // per layer node, into incidence_
  std::vector<std::int32_t> incidence_;                     // 4 tet + corner, per incidence
};

}  // namespace rumble::fem
