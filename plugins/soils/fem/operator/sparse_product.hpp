// C = A B and y = A x for compressed row-major sparse matrices, with the rows shared among
// threads: multigrid's Galerkin products and its V-cycle's products below the mesh's level
// (amg_preconditioner.cpp). Eigen's sparse-sparse product runs on
// one thread and builds its result column-major before copying it into rows: on the 2.1e5-DOF
// hemisphere of bench/fem/fem_static_bench.cpp its A P took 3.4 s of a 4.7 s set-up.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace rumble::fem {

using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;
/// The same with values rounded to float: what multigrid's V-cycle streams below the mesh's level
/// (8 B per nonzero instead of 12; a preconditioner needs no more digits).
using RowSparseFloat = Eigen::SparseMatrix<float, Eigen::RowMajor, int>;

/// A B, compressed, each row's columns sorted (Gustavson's algorithm: each row of A sums the
/// rows of B it selects into a dense accumulator). Entries that cancel to zero are kept, as
/// Eigen's product keeps them. a and b must be compressed; threads >= 1.
RowSparse sparse_product(const RowSparse& a, const RowSparse& b, unsigned threads);

/// y = A x (y resized), rows shared out statically among `threads`: Eigen's sparse-dense
/// product runs on one thread, and on the 2.1e5-DOF hemisphere the V-cycle's products below the
/// mesh's level (the first coarse level holds 0.65 of the mesh's nonzeros) and its transfers
/// took half of a multigrid CG iteration.
void multiply(const RowSparse& a, const Eigen::VectorXd& x, Eigen::VectorXd& y, unsigned threads);
void multiply(const RowSparseFloat& a, const Eigen::VectorXd& x, Eigen::VectorXd& y,
              unsigned threads);
/// y += A x, as multiply().
void multiply_add(const RowSparse& a, const Eigen::VectorXd& x, Eigen::VectorXd& y,
                  unsigned threads);
void multiply_add(const RowSparseFloat& a, const Eigen::VectorXd& x, Eigen::VectorXd& y,
                  unsigned threads);

}  // namespace rumble::fem
