#include "operator/elasticity.hpp"

#include <Eigen/Dense>
#include <sstream>
#include <stdexcept>

namespace rumble::fem {

const soils::SoilProperties& tet_properties(const TetMesh& mesh, const FemSettings& settings,
                                            std::size_t e) {
  const std::size_t layer = mesh.layer[e];
  return layer < settings.layers.size() ? settings.layers[layer].properties : settings.half_space;
}

Lame lame_of(const soils::SoilProperties& p, double relaxed) {
  return {relaxed * p.E * p.nu / ((1.0 + p.nu) * (1.0 - 2.0 * p.nu)), relaxed * p.shear_modulus()};
}

TetGradients tet_gradients(const TetMesh& mesh, const Tetrahedron& t) {
  // The barycentric coordinates of nodes 1..3 are J^-1 (x - x0), J = [x1-x0 x2-x0 x3-x0]: their
  // gradients are the rows of J^-1; node 0's is minus their sum.
  Eigen::Matrix3d J;
  J << mesh.node(t[1]) - mesh.node(t[0]), mesh.node(t[2]) - mesh.node(t[0]),
      mesh.node(t[3]) - mesh.node(t[0]);
  TetGradients g;
  g.volume = J.determinant() / 6.0;
  const Eigen::Matrix3d inverse = J.inverse();
  g.gradient.rightCols<3>() = inverse.transpose();
  g.gradient.col(0) = -g.gradient.rightCols<3>().rowwise().sum();
  return g;
}

CsrMatrix assemble_stiffness(const TetMesh& mesh, const FemSettings& settings) {
  CsrMatrix K(mesh);
  // The relaxed modulus under the Maxwell mechanisms (E is theirs at the band's centre).
  const double relaxed = settings.damping.relaxed_modulus_factor();
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    const Tetrahedron& t = mesh.tets[e];
    const TetGradients g = tet_gradients(mesh, t);
    if (!(g.volume > 0.0)) {
      std::ostringstream m;
      m << "fem: tetrahedron " << e << " of the mesh has volume " << g.volume
        << " m^3; the mesh is degenerate (remesh, or check a user mesh for inverted elements)";
      throw std::invalid_argument(m.str());
    }
    const auto [lambda, mu] = lame_of(tet_properties(mesh, settings, e), relaxed);
    // K_ab = V (lambda g_a g_b^T + mu g_b g_a^T + mu (g_a . g_b) I).
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        const Eigen::Vector3d ga = g.gradient.col(a), gb = g.gradient.col(b);
        Eigen::Matrix3d block = lambda * ga * gb.transpose() + mu * gb * ga.transpose();
        block.diagonal().array() += mu * ga.dot(gb);
        block *= g.volume;
        for (int c = 0; c < 3; ++c) {
          double* row = K.block_row(t[a], t[b], c);
          for (int d = 0; d < 3; ++d) row[d] += block(c, d);
        }
      }
  }
  return K;
}

Eigen::VectorXd lumped_mass(const TetMesh& mesh, const FemSettings& settings) {
  Eigen::VectorXd m = Eigen::VectorXd::Zero(mesh.node_count());
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    const double share = tet_properties(mesh, settings, e).rho * tet_volume(mesh, mesh.tets[e]) / 4;
    for (std::int32_t a : mesh.tets[e]) m[a] += share;
  }
  return m;
}

}  // namespace rumble::fem
