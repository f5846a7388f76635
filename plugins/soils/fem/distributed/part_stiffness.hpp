// K and the lumped mass on one rank's part of the mesh (mesh_partition.hpp), from the soil's own
// element kernels (operator/elasticity.hpp) over the part's tetrahedra.
//
// K: each rank's rows hold its tetrahedra's elements, so a node's rows summed over the ranks
// are K's. An entry between two shared nodes may gather elements of several ranks; summed there
// in pieces, each piece rounded to float when the step reads K in single precision, it would
// differ from one process's K by the rounding (6e-8 of it) and the ranks' results from one
// process's by as much. So each such entry is summed whole, once, and kept by the lowest rank
// that holds it (the others hold zeros there): every entry of K is then rounded once, as on one
// process. Off the diagonal, K_ji is set to K_ij^T for i before j in rank 0's node order, the
// upper blocks one process's step reads (operator/symmetric_blocks.hpp): the ranks' K is
// symmetric as its is.
//
// The mass: each rank's share of its tetrahedra, summed over the shared nodes' ranks and copied
// back, so every copy of a node holds the same mass.
#pragma once

#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <Eigen/Core>

#include "distributed/mesh_partition.hpp"
#include "operator/csr_matrix.hpp"

namespace rumble::fem {

/// Makes K, assembled from the part's tetrahedra (assemble_stiffness(part.mesh, ...)), the part's
/// K as above. Collective over comm.
void complete_shared_entries(const MeshPartition& part, CsrMatrix& K, MPI_Comm comm);

/// The whole lumped mass [kg] of each of the part's nodes from the part's own (lumped_mass(
/// part.mesh, ...)). Collective.
void complete_mass(const MeshPartition& part, Eigen::VectorXd& mass);

}  // namespace rumble::fem
