// Eigen's compressed row-major sparse matrix with 32-bit indices: the effective matrices' and the
// geometric multigrid's coarse level and interpolation (operator/effective_matrix.hpp,
// statics/coarse_level.hpp), which hand their arrays to PETSc's AIJ without a copy.
#pragma once

#include <Eigen/SparseCore>

namespace rumble::fem {

using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

}  // namespace rumble::fem
