// MPI in the engine (docs/decisions/0012-distributed-soil.md §2): started only when it is used,
// under a launcher (mpirun, srun) or when a plugin asks for a communicator; finished once, at
// exit. Nothing here is MPI-typed: communicators cross as MPI's Fortran handles (integers), so
// that no other room includes <mpi.h>. OpenMPI's start costs about 0.1 s and AddressSanitizer
// counts what it never frees (docs/toolchain.md §9): a process that never asks never pays.
#pragma once

#include <cstdint>
#include <string>

namespace rumble::parallel {

/// Whether this process was started by an MPI launcher: OpenMPI's mpirun sets
/// OMPI_COMM_WORLD_SIZE, PMI-2 and PMIx launchers (MPICH's, Slurm's srun) PMI_SIZE or PMIX_RANK.
/// Read from the environment: MPI is not started by asking.
bool launched();

/// The rank count the launcher asked for (OMPI_COMM_WORLD_SIZE or PMI_SIZE), 1 without a
/// launcher; read before MPI starts, to check a scenario against it early.
int launched_size();

/// This process's rank as the launcher numbered it (OMPI_COMM_WORLD_RANK, PMI_RANK or
/// PMIX_RANK), 0 without a launcher: rank 0 is the engine, the others serve it (decision 0012).
int launched_rank();

/// Starts MPI if it is not running (once per process; MPI_THREAD_SERIALIZED: a Jacobi step calls
/// the soil from a second thread, one call at a time). Throws RunError when it cannot, with what
/// to check. Started by someone else (a plugin, against our rule) counts as started.
void start();

/// Whether MPI is running in this process (started and not finished).
bool running();

/// This process's rank in MPI_COMM_WORLD and the world's size; 0 and 1 while MPI is not running.
int world_rank();
int world_size();

/// The MPI library's own description (MPI_Get_library_version's first line: "Open MPI v4.1.4,
/// ..."), available without starting MPI; and the MPI standard version it implements ("3.1").
std::string library_version();
std::string standard_version();

/// Finishes MPI if this process started it, after every communicator it handed out was freed;
/// on rank 0 of a launch it first releases the other ranks. Called once at the end of main; a
/// second call does nothing.
void finish();

/// A duplicate of MPI_COMM_WORLD (world = true) or MPI_COMM_SELF, made for one plugin instance so
/// that its messages never meet anyone else's; freed on destruction. Starts MPI when needed.
class Communicator {
 public:
  explicit Communicator(bool world);
  ~Communicator();
  Communicator(const Communicator&) = delete;
  Communicator& operator=(const Communicator&) = delete;

  /// MPI_Comm_c2f of the duplicate: what rumble_host.communicator hands a plugin.
  std::int64_t fortran_handle() const { return fortran_; }
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  std::int64_t fortran_ = 0;
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace rumble::parallel
