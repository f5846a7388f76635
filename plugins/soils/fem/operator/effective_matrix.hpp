// Linear combinations of the FEM soil's operators as one sparse symmetric matrix for CHOLMOD:
//   k K + m M + S (when springs) + d D,
// K the elastic stiffness, M the lumped mass, S and D the boundary's spring and dashpot blocks;
// fixed DOFs become identity rows and columns. The static matrix is K + S; Newmark's effective
// matrix K (1 + c1 a1) + (c0 + c1 a0) M + S + c1 D.
#pragma once

// GCC 12 reports a null dereference inside Eigen's SparseCompressedBase when insert() is inlined
// (a false positive: the matrix is reserved first); the pragma must cover the header itself.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>
#pragma GCC diagnostic pop
#include <SuiteSparse_config.h>

#include <vector>

#include "operator/row_sparse.hpp"
#include "operator/soil_operator.hpp"

namespace rumble::fem {

/// CHOLMOD's 64-bit interface (cholmod_l): docs/numerics.md §4.2, the int one fails near 1e6 DOFs.
using LongSparse = Eigen::SparseMatrix<double, Eigen::ColMajor, SuiteSparse_long>;

struct Combination {
  double stiffness = 0.0;  // k
  double mass = 0.0;       // m [1/s^2 x kg -> N/m]
  bool springs = false;    // + S
  double dashpots = 0.0;   // d [1/s]
};

/// One boundary node's block of the combination, row-major 3 x 3: c.springs S + c.dashpots D,
/// symmetric to the bit (its upper part copies the lower: n_r n_d and n_d n_r may round apart).
void boundary_block(const BoundaryNode& b, const Combination& c, double out[9]);
/// The boundary's blocks of the combination per node, row-major 3 x 3 (9 per node, zero off the
/// truncation surface): boundary_block at each boundary node.
std::vector<double> boundary_blocks(const SoilOperator& op, const Combination& c);

/// The lower triangle of the combination, CSC (for CHOLMOD).
LongSparse lower_combination(const SoilOperator& op, const Combination& c);
/// The whole combination, compressed rows with 32-bit indices (for multigrid, whose products
/// read rows): built directly, without the lower triangle's 16 B per nonzero on the way.
RowSparse full_combination(const SoilOperator& op, const Combination& c);

}  // namespace rumble::fem
