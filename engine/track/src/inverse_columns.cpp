#include "track/inverse_columns.hpp"

#include <algorithm>

namespace rumble {

void InverseColumns::resize(std::size_t n, std::size_t capacity) {
  n_ = n;
  capacity_ = std::min(std::max<std::size_t>(capacity, 4), n);
  storage_.assign(n_ * capacity_, 0.0);
  slot_of_.assign(n_, -1);
  dof_in_.assign(capacity_, n_);
  last_use_.assign(capacity_, 0);
}

void InverseColumns::clear() {
  std::fill(slot_of_.begin(), slot_of_.end(), -1);
  std::fill(dof_in_.begin(), dof_in_.end(), n_);
  std::fill(last_use_.begin(), last_use_.end(), 0);
}

const double* InverseColumns::find(std::size_t dof) {
  ++clock_;
  if (const std::ptrdiff_t s = slot_of_[dof]; s >= 0) {
    last_use_[static_cast<std::size_t>(s)] = clock_;
    return &storage_[static_cast<std::size_t>(s) * n_];
  }
  return nullptr;
}

double* InverseColumns::claim(std::size_t dof) {
  // A miss (a wheel entered a new element): take an empty slot, else the least recently used.
  const auto slot = static_cast<std::size_t>(std::min_element(last_use_.begin(), last_use_.end()) -
                                             last_use_.begin());
  if (dof_in_[slot] < n_) slot_of_[dof_in_[slot]] = -1;
  dof_in_[slot] = dof;
  slot_of_[dof] = static_cast<std::ptrdiff_t>(slot);
  last_use_[slot] = clock_;
  double* col = &storage_[slot * n_];
  std::fill(col, col + n_, 0.0);
  col[dof] = 1.0;
  return col;
}

}  // namespace rumble
