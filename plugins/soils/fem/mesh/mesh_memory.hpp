// What a mesh will cost in memory, held against what the machine has free before it is spent
// (issue #30: a mesh that cannot run is refused before meshing, not swapped or OOM-killed).
#pragma once

#include <rumble/host_resources.hpp>
#include <sstream>
#include <stdexcept>
#include <string>

namespace rumble::fem {

/// Peak resident memory of a FEM run per degree of freedom [bytes]: B7 (1.03e6 DOFs) peaked at
/// 4.15 GB with meshing, the static multigrid and the explicit step (docs/fem-soil.md §7).
inline constexpr double kPeakBytesPerDof = 4.0e3;

/// Throws std::invalid_argument ("<where>: ..." with the estimate, what is available and `fix`;
/// `where` names the key: "fem: params/mesh") when `dofs` would need more memory at a run's peak
/// than the machine has available now.
inline void check_memory_for(double dofs, const std::string& where, const std::string& fix) {
  const double need = dofs * kPeakBytesPerDof;
  const double available = available_memory_bytes();
  if (need <= available) return;
  std::ostringstream m;
  m.precision(3);
  m << where << ": a mesh of about " << dofs << " degrees of freedom needs about " << need / 1e9
    << " GB at a run's peak (about " << kPeakBytesPerDof * 1e-3
    << " kB per DOF: meshing, the static multigrid and the step; docs/fem-soil.md §7), more "
    << "than the " << available / 1e9
    << " GB this machine has available now (MemAvailable, or the cgroup's limit); " << fix
    << ", or free memory and run again";
  throw std::invalid_argument(m.str());
}

}  // namespace rumble::fem
