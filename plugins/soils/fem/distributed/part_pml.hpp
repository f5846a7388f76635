// The perfectly matched layer on one rank's part of the mesh (issue #33; docs/fem-soil.md §8,
// "The matched layer on the ranks"; the layer itself: boundary/pml.hpp). Each rank's layer holds
// the layer tetrahedra of its part, each tetrahedron on one rank with its memory. A node on the
// part's border is a layer node on every rank that holds it when it is one on any (its layer
// tetrahedra may all be another rank's), and its mass side, summed from its tetrahedra, is
// summed over the ranks: every copy steps the node alike. The step then sums the tetrahedra's
// forces at those nodes over the ranks each sub-step (time/explicit_solver.cpp). Collective.
#pragma once

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include "boundary/pml.hpp"
#include "distributed/mesh_partition.hpp"
#include "fem_settings.hpp"
#include "mesh/pml_profile.hpp"

namespace rumble::fem {

/// Rank 0's `profile` on every rank (the others' argument is not read). Collective.
PmlProfile from_root(const PmlProfile& profile, MPI_Comm comm);

/// The layer of part's tetrahedra whose centroid lies beyond `profile`'s physical box (the whole
/// mesh's, the same on every rank), completed over the ranks as above; its largest damping is
/// the ranks' largest, so that every rank bounds its step alike.
PmlLayer part_pml(const MeshPartition& part, const FemSettings& settings, const PmlProfile& profile,
                  MPI_Comm comm);

}  // namespace rumble::fem
