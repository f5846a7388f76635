// Small-strain, linear isotropic elasticity on linear tetrahedra: the global stiffness K [N/m]
// and the row-sum lumped mass [kg] per node (rho V / 4 to each node of a tetrahedron, which is
// the row sum of the consistent mass of a linear tetrahedron).
#pragma once

#include <Eigen/Core>

#include "fem_settings.hpp"
#include "mesh/tet_mesh.hpp"
#include "operator/csr_matrix.hpp"

namespace rumble::fem {

/// Shape-function gradients [1/m] (columns) and volume [m^3] of a tetrahedron.
struct TetGradients {
  Eigen::Matrix<double, 3, 4> gradient;
  double volume = 0.0;
};
TetGradients tet_gradients(const TetMesh& mesh, const Tetrahedron& t);

/// K with the material of each tetrahedron's layer (its relaxed modulus under the Maxwell
/// mechanisms: DampingRequest::relaxed_modulus_factor). Throws std::invalid_argument for a
/// degenerate tetrahedron (volume <= 0), naming it.
CsrMatrix assemble_stiffness(const TetMesh& mesh, const FemSettings& settings);

/// Lumped mass per node [kg].
Eigen::VectorXd lumped_mass(const TetMesh& mesh, const FemSettings& settings);

/// Lame's constants [Pa] of a soil, its modulus scaled by `relaxed` (the relaxed modulus under
/// the Maxwell mechanisms: DampingRequest::relaxed_modulus_factor).
struct Lame {
  double lambda = 0.0, mu = 0.0;
};
Lame lame_of(const soils::SoilProperties& p, double relaxed);

/// The layer's properties of tetrahedron e.
const soils::SoilProperties& tet_properties(const TetMesh& mesh, const FemSettings& settings,
                                            std::size_t e);

}  // namespace rumble::fem
