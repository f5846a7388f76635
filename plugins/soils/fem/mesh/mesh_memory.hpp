// What a mesh will cost in memory, held against what the machine has free before it is spent
// (issue #30: a mesh that cannot run is refused before meshing, not swapped or OOM-killed), by
// the soil's memory model (memory_model.hpp); and the process's resident memory, which the
// soil's estimate after the assembly starts from.
#pragma once

#include <rumble/host_resources.hpp>
#include <sstream>
#include <stdexcept>
#include <string>

#include "memory_model.hpp"

namespace rumble::fem {

/// A run's peak for a million DOFs [bytes]: what mesh.max_dofs' messages quote.
inline double peak_bytes_per_million_dofs() {
  return memory::run_peak_bytes(1e6);
}

/// Throws std::invalid_argument ("<where>: ..." with the estimate, what is available and `fix`;
/// `where` names the key: "fem: params/mesh") when `dofs` would need more memory at a run's peak
/// than the machine has available now.
inline void check_memory_for(double dofs, const std::string& where, const std::string& fix) {
  const double need = memory::run_peak_bytes(dofs);
  const double available = available_memory_bytes();
  if (need <= available) return;
  std::ostringstream m;
  m.precision(3);
  m << where << ": a mesh of about " << dofs << " degrees of freedom needs about " << need / 1e9
    << " GB at a run's peak (" << need / dofs * 1e-3 << " kB per DOF: "
    << (dofs <= memory::kFactorLimitDofs ? "the statics' Cholesky factor"
                                         : "the statics' GAMG set-up")
    << "; docs/fem-soil.md section 7.2), more than the " << available / 1e9
    << " GB this machine has available now (MemAvailable, or the cgroup's limit); " << fix
    << ", or free memory and run again";
  throw std::invalid_argument(m.str());
}

/// The process's resident memory now and its peak so far [bytes] (/proc/self/status; 0 where
/// it does not tell).
struct ResidentMemory {
  double now = 0.0, peak = 0.0;
};
ResidentMemory resident_memory();

}  // namespace rumble::fem
