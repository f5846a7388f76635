#include "mesh/mesh_memory.hpp"

#include <fstream>

namespace rumble::fem {

ResidentMemory resident_memory() {
  ResidentMemory r;
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    double* into = line.rfind("VmRSS:", 0) == 0   ? &r.now
                   : line.rfind("VmHWM:", 0) == 0 ? &r.peak
                                                  : nullptr;
    if (into == nullptr) continue;
    std::istringstream words(line.substr(6));
    double kib = 0.0;
    words >> kib;  // "VmRSS:   218292 kB"
    *into = 1024.0 * kib;
  }
  return r;
}

}  // namespace rumble::fem
