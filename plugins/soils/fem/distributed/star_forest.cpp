#include "distributed/star_forest.hpp"

#include <petscsf.h>

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "statics/petsc_session.hpp"

namespace rumble::fem {

struct StarForest::Petsc {
  PetscSF sf = nullptr;
  // Contiguous types of 1-3 doubles or ints, per (base, width): PETSc packs them with its own
  // kernels of that block size (a derived type of one basic type is what it supports).
  mutable std::map<std::pair<MPI_Datatype, int>, MPI_Datatype> units;
};

StarForest::StarForest(MPI_Comm comm, std::int32_t roots, const std::vector<ForestLeaf>& leaves)
    : petsc_(std::make_unique<Petsc>()),
      roots_(roots),
      leaves_(static_cast<std::int32_t>(leaves.size())) {
  check_leaves(comm, roots, leaves);
  petsc_check(PetscSFCreate(comm, &petsc_->sf), "PetscSFCreate");
  std::vector<PetscInt> local(leaves.size());
  std::vector<PetscSFNode> remote(leaves.size());
  for (std::size_t k = 0; k < leaves.size(); ++k) {
    local[k] = leaves[k].local;
    remote[k].rank = leaves[k].rank;
    remote[k].index = leaves[k].remote;
    extent_ = std::max(extent_, leaves[k].local + 1);
  }
  petsc_check(PetscSFSetGraph(petsc_->sf, roots, leaves_, local.data(), PETSC_COPY_VALUES,
                              remote.data(), PETSC_COPY_VALUES),
              "PetscSFSetGraph");
  petsc_check(PetscSFSetUp(petsc_->sf), "PetscSFSetUp");
  for (int width = 1; width <= 3; ++width) {  // (the units made now: unit() then only finds)
    unit(MPI_DOUBLE, width);
    unit(MPI_INT, width);
  }
}

void StarForest::check_leaves(MPI_Comm comm, std::int32_t roots,
                              const std::vector<ForestLeaf>& leaves) {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  std::vector<std::int32_t> roots_of(static_cast<std::size_t>(ranks));
  MPI_Allgather(&roots, 1, MPI_INT32_T, roots_of.data(), 1, MPI_INT32_T, comm);
  for (const ForestLeaf& leaf : leaves)
    if (leaf.local < 0 || leaf.rank < 0 || leaf.rank >= ranks || leaf.remote < 0 ||
        leaf.remote >= roots_of[static_cast<std::size_t>(leaf.rank)])
      throw std::logic_error("fem: a star forest's leaf " + std::to_string(leaf.local) +
                             " copies point " + std::to_string(leaf.remote) + " of rank " +
                             std::to_string(leaf.rank) + ", which has " +
                             (leaf.rank >= 0 && leaf.rank < ranks
                                  ? std::to_string(roots_of[static_cast<std::size_t>(leaf.rank)])
                                  : std::string("no")) +
                             " roots");
}

void StarForest::make_exchange_buffers() {
  std::vector<double> root_values(3 * static_cast<std::size_t>(roots_), 0.0);
  std::vector<double> leaf_values(3 * static_cast<std::size_t>(extent_), 0.0);
  to_leaves(root_values.data(), leaf_values.data(), 3);
  sum_to_roots(leaf_values.data(), root_values.data(), 3);
}

StarForest::~StarForest() {
  for (auto& [key, type] : petsc_->units) MPI_Type_free(&type);
  PetscSFDestroy(&petsc_->sf);
}

MPI_Datatype StarForest::unit(MPI_Datatype base, int width) const {
  if (width == 1) return base;
  auto [at, made] = petsc_->units.try_emplace({base, width}, MPI_DATATYPE_NULL);
  if (made) {
    MPI_Type_contiguous(width, base, &at->second);
    MPI_Type_commit(&at->second);
  }
  return at->second;
}

void StarForest::to_leaves_begin(const double* root_values, double* leaf_values, int width) const {
  petsc_check(
      PetscSFBcastBegin(petsc_->sf, unit(MPI_DOUBLE, width), root_values, leaf_values, MPI_REPLACE),
      "PetscSFBcastBegin");
}

void StarForest::to_leaves_end(const double* root_values, double* leaf_values, int width) const {
  petsc_check(
      PetscSFBcastEnd(petsc_->sf, unit(MPI_DOUBLE, width), root_values, leaf_values, MPI_REPLACE),
      "PetscSFBcastEnd");
}

void StarForest::to_leaves(const int* root_values, int* leaf_values, int width) const {
  const MPI_Datatype type = unit(MPI_INT, width);
  petsc_check(PetscSFBcastBegin(petsc_->sf, type, root_values, leaf_values, MPI_REPLACE),
              "PetscSFBcastBegin");
  petsc_check(PetscSFBcastEnd(petsc_->sf, type, root_values, leaf_values, MPI_REPLACE),
              "PetscSFBcastEnd");
}

void StarForest::sum_to_roots_begin(const double* leaf_values, double* root_values,
                                    int width) const {
  petsc_check(
      PetscSFReduceBegin(petsc_->sf, unit(MPI_DOUBLE, width), leaf_values, root_values, MPI_SUM),
      "PetscSFReduceBegin");
}

void StarForest::sum_to_roots_end(const double* leaf_values, double* root_values, int width) const {
  petsc_check(
      PetscSFReduceEnd(petsc_->sf, unit(MPI_DOUBLE, width), leaf_values, root_values, MPI_SUM),
      "PetscSFReduceEnd");
}

void StarForest::copy_to_roots(const double* leaf_values, double* root_values, int width) const {
  const MPI_Datatype type = unit(MPI_DOUBLE, width);
  petsc_check(PetscSFReduceBegin(petsc_->sf, type, leaf_values, root_values, MPI_REPLACE),
              "PetscSFReduceBegin");
  petsc_check(PetscSFReduceEnd(petsc_->sf, type, leaf_values, root_values, MPI_REPLACE),
              "PetscSFReduceEnd");
}

std::vector<int> StarForest::root_degrees() const {
  const PetscInt* degree = nullptr;
  petsc_check(PetscSFComputeDegreeBegin(petsc_->sf, &degree), "PetscSFComputeDegreeBegin");
  petsc_check(PetscSFComputeDegreeEnd(petsc_->sf, &degree), "PetscSFComputeDegreeEnd");
  std::vector<int> out(static_cast<std::size_t>(roots_), 0);
  for (std::int32_t k = 0; k < roots_; ++k) out[k] = static_cast<int>(degree[k]);
  return out;  // (the degrees stay the forest's)
}

}  // namespace rumble::fem
