// Columns of A^-1 for the rail DOFs under the wheels, cached. A wheel's contact point moves by
// less than an element per micro-step, so the columns of the same four DOFs serve hundreds of
// micro-steps, and the track's response to a unit contact force, z = A^-1 N (N: the contact
// point's four shape values), costs four vector updates instead of a banded solve per wheel.
// Fixed capacity, the least recently used column evicted, storage allocated once: nothing is
// allocated per micro-step.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "track/banded_matrix.hpp"

namespace rumble {

class InverseColumns {
 public:
  /// n: size of A; capacity: columns kept (at least 4, the DOFs of one contact point).
  void resize(std::size_t n, std::size_t capacity);
  /// Forget every column: A has changed (a new micro-step size).
  void clear();
  /// A^-1 e_dof (n values), solved with the factorized `a` when not cached. Valid until the
  /// next call.
  const double* column(std::size_t dof, const BandedSymmetric& a) {
    return column_by(dof, [&a](double* x) { a.solve(x); });
  }
  /// The same for any A: `solve(x)` overwrites x (n values) with A^-1 x.
  template <class Solve>
  const double* column_by(std::size_t dof, Solve&& solve) {
    if (const double* cached = find(dof)) return cached;
    double* col = claim(dof);
    solve(col);
    ++solves_;
    return col;
  }

  std::uint64_t solves() const { return solves_; }  // columns computed so far

 private:
  const double* find(std::size_t dof);  // the cached column, or null
  double* claim(std::size_t dof);       // a slot for dof, holding e_dof

  std::size_t n_ = 0, capacity_ = 0;
  std::vector<double> storage_;          // capacity_ columns of n_ values
  std::vector<std::ptrdiff_t> slot_of_;  // per DOF: its slot, or -1
  std::vector<std::size_t> dof_in_;      // per slot: its DOF, or n_ when empty
  std::vector<std::uint64_t> last_use_;  // per slot
  std::uint64_t clock_ = 0, solves_ = 0;
};

}  // namespace rumble
