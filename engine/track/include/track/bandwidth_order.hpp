// A bandwidth-reducing order of a symmetric sparse matrix's unknowns (reverse Cuthill-McKee,
// Boost.Graph), so that a soil meshed in any node order can be held in band storage
// (IntegratedSoil). For a 3D mesh of n nodes the half bandwidth falls from about n to about
// n^(2/3) times the DOFs per node.
#pragma once

#include <Eigen/SparseCore>
#include <cstddef>
#include <vector>

namespace rumble {

/// order[k]: the unknown that goes to position k. The pattern is that of `a` (symmetric).
std::vector<Eigen::Index> bandwidth_reducing_order(const Eigen::SparseMatrix<double>& a);

/// Half bandwidth of `a` with its unknowns in `order` (identity when order is empty).
std::size_t half_bandwidth(const Eigen::SparseMatrix<double>& a,
                           const std::vector<Eigen::Index>& order = {});

}  // namespace rumble
