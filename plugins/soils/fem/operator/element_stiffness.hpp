// K u without K's rows: each tetrahedron's K_e u_e formed from its nodes' positions when the
// product is asked for (issue #33, a rank's memory per DOF; docs/fem-soil.md §8, "K without its
// rows"). K's assembled rows in double take about 540 B per DOF (45 nonzeros per DOF on the
// graded meshes, a double and a column index each); this product reads the mesh's nodes (held
// anyway) and keeps a copy of the tetrahedra in a cache-friendly order, about 35 B per DOF.
//
// For a linear tetrahedron with gradients g_a of its shape functions and volume V, K_ab =
// V (lambda g_a g_b^T + mu g_b g_a^T + mu (g_a . g_b) I) (elasticity.cpp), so that
//   sum_b K_ab u_b = V sigma g_a,   sigma = lambda tr(G) I + mu (G + G^T),   G = sum_b u_b g_b^T:
// the displacement gradient G, the stress sigma and its traction on each node, about 200
// floating-point operations per tetrahedron against 576 for its 16 blocks. The sums differ from
// the assembled rows' by rounding alone (tests/fem/element_stiffness_test.cpp: 1e-14 of the
// product). Its speed against the rows': bench/fem/stiffness_product_bench.cpp, docs/fem-soil.md
// §8.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fem_settings.hpp"
#include "mesh/tet_mesh.hpp"
#include "operator/elasticity.hpp"

namespace rumble::fem {

class ElementStiffness {
 public:
  /// The mesh's nodes are read at every product and must outlive this; the settings give each
  /// layer's material (its relaxed modulus, as assemble_stiffness).
  ElementStiffness(const TetMesh& mesh, const FemSettings& settings);

  /// y = K x over the mesh's tetrahedra (3 DOFs per node; no boundary blocks, no fixed nodes),
  /// on `threads` OpenMP threads: each sums its share of the tetrahedra into its own copy of y,
  /// the copies added in thread order (the same sums run after run on the same team).
  void times(const double* x, double* y, unsigned threads) const;
  /// K's diagonal from the same elements.
  Eigen::VectorXd diagonal() const;
  /// Row a (0-3) of tetrahedron e's K_e: the blocks K_a0 to K_a3 above, its nodes in the mesh's
  /// order, 3 DOFs each (a Galerkin product formed element by element).
  Eigen::Matrix<double, 3, 12> element_row(std::size_t e, int a) const;
  /// Memory held [bytes]: the table, the sorted tetrahedra and the threads' copies of y.
  std::size_t bytes() const;
  /// Frees the sorted tetrahedra and the threads' copies (made again at the next product).
  void release() const;

 private:
  /// Copies the tetrahedra into tets_ and layer_ at the first product (a back end that keeps
  /// its rows never pays for them).
  void sort_tetrahedra() const;

  const TetMesh& mesh_;
  std::vector<Lame> lame_;  // per layer; the last the half-space's

  // The tetrahedra and their layers, copied in the order of their lowest node: the nodes are in
  // Morton order (mesh/node_order.hpp), so consecutive tetrahedra read and add to nearby nodes
  // (18 B a tetrahedron, about 35 B per DOF). In gmsh's order the graded stiff example's
  // product took 6.2 times the rows' (107 ns a tetrahedron), its nodes' reads and sums missing
  // the cache; through a sorted index instead of a copy, the tetrahedra's own reads missed
  // (bench/fem/stiffness_product_bench.cpp).
  mutable std::vector<Tetrahedron> tets_;
  mutable std::vector<std::uint16_t> layer_;
  mutable std::vector<double> copies_;  // (threads - 1) copies of y
};

}  // namespace rumble::fem
