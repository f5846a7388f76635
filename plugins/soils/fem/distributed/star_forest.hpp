// PETSc's star forest (PetscSF) between the ranks, behind a small class so that no header of the
// FEM soil includes PETSc's (docs/decisions/0012-distributed-soil.md §4: the halo exchange is
// PETSc's). A forest links leaves (points of this rank that copy another rank's) to roots (the
// points that rank owns): `to_leaves` copies each root's values to its leaves (PetscSFBcast),
// `sum_to_roots` adds the leaves' values to their roots' (PetscSFReduce with MPI_SUM; PETSc
// adds the ranks' contributions in one fixed order, so the sums repeat run after run). Values
// are `width` doubles or ints per point.
//
// Roots and leaves may lie in one array when no point is both (the halo: the owned shared nodes
// are roots, the ghosts leaves): PETSc reads the leaves in Begin and writes the roots in End.
#pragma once

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace rumble::fem {

/// A leaf: this rank's point `local` copies point `remote` of rank `rank`.
struct ForestLeaf {
  std::int32_t local = 0;
  int rank = 0;
  std::int32_t remote = 0;
};

class StarForest {
 public:
  /// roots: this rank's points others may copy (0 .. roots - 1); leaves: this rank's copies.
  /// Collective over comm. Throws std::logic_error for a leaf that copies no root (PETSc's
  /// optimised build would read and write past the arrays).
  StarForest(MPI_Comm comm, std::int32_t roots, const std::vector<ForestLeaf>& leaves);

  /// Makes the exchanges of 3 doubles per point (to_leaves, sum_to_roots) once, so that later
  /// ones allocate nothing and cannot fail on one rank alone: PETSc keeps their buffers (a
  /// point's 24 bytes each way). For the halo, whose exchanges the step's product makes inside
  /// an OpenMP region (distributed_operator.hpp). Collective.
  void make_exchange_buffers();
  ~StarForest();
  StarForest(const StarForest&) = delete;
  StarForest& operator=(const StarForest&) = delete;

  std::int32_t roots() const { return roots_; }
  std::int32_t leaves() const { return leaves_; }

  /// leaf values = their roots' (width doubles per point). Collective.
  void to_leaves_begin(const double* root_values, double* leaf_values, int width) const;
  void to_leaves_end(const double* root_values, double* leaf_values, int width) const;
  void to_leaves(const double* root_values, double* leaf_values, int width) const {
    to_leaves_begin(root_values, leaf_values, width);
    to_leaves_end(root_values, leaf_values, width);
  }
  void to_leaves(const int* root_values, int* leaf_values, int width) const;

  /// root values += their leaves' (width doubles per point). Collective.
  void sum_to_roots_begin(const double* leaf_values, double* root_values, int width) const;
  void sum_to_roots_end(const double* leaf_values, double* root_values, int width) const;
  void sum_to_roots(const double* leaf_values, double* root_values, int width) const {
    sum_to_roots_begin(leaf_values, root_values, width);
    sum_to_roots_end(leaf_values, root_values, width);
  }
  /// root values = one of their leaves' (any: the caller's leaves of a root agree), roots
  /// without a leaf unchanged. Collective.
  void copy_to_roots(const double* leaf_values, double* root_values, int width) const;

  /// For each root, how many leaves copy it (PetscSFComputeDegree). Collective.
  std::vector<int> root_degrees() const;

 private:
  struct Petsc;
  /// The MPI type of `width` values of `base`, made once per width and kept.
  MPI_Datatype unit(MPI_Datatype base, int width) const;

  static void check_leaves(MPI_Comm comm, std::int32_t roots,
                           const std::vector<ForestLeaf>& leaves);

  std::unique_ptr<Petsc> petsc_;
  std::int32_t roots_ = 0, leaves_ = 0;
  std::int32_t extent_ = 0;  // the leaves' largest local point + 1
};

}  // namespace rumble::fem
