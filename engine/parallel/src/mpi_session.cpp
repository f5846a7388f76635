#include "parallel/mpi_session.hpp"

// OpenMPI's C++ bindings are deprecated and unused here: the C interface alone.
#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <algorithm>
#include <cstdlib>
#include <mutex>
#include <string_view>

#include "core/errors.hpp"
#include "parallel/mirror_transport.hpp"

namespace rumble::parallel {
namespace {

std::mutex start_mutex;     // start() may be asked from two threads (a Jacobi step)
bool started_here = false;  // this process called MPI_Init_thread (so it calls MPI_Finalize)
bool finished = false;

const char* environment(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' ? v : nullptr;
}

bool released = false;  // rank 0 of a launch released the servers

bool mpi_running() {
  int initialized = 0, finalized = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  return initialized != 0 && finalized == 0;
}

}  // namespace

bool launched() {
  return environment("OMPI_COMM_WORLD_SIZE") != nullptr || environment("PMI_SIZE") != nullptr ||
         environment("PMIX_RANK") != nullptr;
}

int launched_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
    if (const char* v = environment(name)) {
      const int n = std::atoi(v);
      if (n > 0) return n;
    }
  }
  return 1;
}

int launched_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"}) {
    if (const char* v = environment(name)) return std::max(0, std::atoi(v));
  }
  return 0;
}

void start() {
  const std::lock_guard<std::mutex> lock(start_mutex);
  if (mpi_running()) return;
  if (finished) throw RunError("MPI was asked for after rumble finished it (an engine defect)");
  int provided = MPI_THREAD_SINGLE;
  if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided) != MPI_SUCCESS) {
    throw RunError("MPI did not start (" + library_version() +
                   "): check that `mpirun` belongs to the MPI rumble was built with");
  }
  started_here = true;
  if (provided < MPI_THREAD_SERIALIZED) {
    throw RunError("MPI (" + library_version() +
                   ") offers no MPI_THREAD_SERIALIZED, which a jacobi step needs (the soil is "
                   "called from a second thread); use an MPI built with thread support");
  }
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (launched_size() > 1 && size == 1) {
    throw RunError("the launcher started " + std::to_string(launched_size()) +
                   " processes but MPI sees each alone (a world of 1): the `mpirun` used belongs "
                   "to another MPI than rumble's (" +
                   library_version() + "); use that MPI's mpirun (Debian: openmpi-bin)");
  }
}

bool running() {
  return mpi_running();
}

int world_rank() {
  if (!mpi_running()) return 0;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

int world_size() {
  if (!mpi_running()) return 1;
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

std::string library_version() {
  char text[MPI_MAX_LIBRARY_VERSION_STRING] = {};
  int length = 0;
  MPI_Get_library_version(text, &length);
  std::string_view v(text, static_cast<std::size_t>(length));
  v = v.substr(0, v.find_first_of("\n,"));  // "Open MPI v4.1.4, package: ...": the name alone
  return std::string(v);
}

std::string standard_version() {
  int version = 0, subversion = 0;
  MPI_Get_version(&version, &subversion);
  return std::to_string(version) + "." + std::to_string(subversion);
}

void finish() {
  const std::lock_guard<std::mutex> lock(start_mutex);
  if (started_here && mpi_running()) {
    if (launched() && world_rank() == 0 && world_size() > 1 && !released) {
      release_servers();
      released = true;
    }
    MPI_Finalize();
  }
  finished = finished || started_here;
}

Communicator::Communicator(bool world) {
  start();
  MPI_Comm dup = MPI_COMM_NULL;
  MPI_Comm_dup(world ? MPI_COMM_WORLD : MPI_COMM_SELF, &dup);
  MPI_Comm_rank(dup, &rank_);
  MPI_Comm_size(dup, &size_);
  fortran_ = static_cast<std::int64_t>(MPI_Comm_c2f(dup));
}

Communicator::~Communicator() {
  if (!mpi_running()) return;  // MPI_Finalize freed it
  MPI_Comm comm = MPI_Comm_f2c(static_cast<MPI_Fint>(fortran_));
  MPI_Comm_free(&comm);
}

}  // namespace rumble::parallel
