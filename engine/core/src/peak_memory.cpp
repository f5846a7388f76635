#include "core/peak_memory.hpp"

#include <fstream>
#include <sstream>

#include "core/malloc_policy.hpp"

namespace rumble {

std::uint64_t peak_resident_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) != 0) continue;
    std::istringstream words(line.substr(6));
    std::uint64_t kib = 0;
    words >> kib;  // "VmHWM:   218292 kB"
    return kib * 1024;
  }
  return 0;
}

bool restart_peak_resident() {
  std::ofstream clear_refs("/proc/self/clear_refs");
  clear_refs << "5";
  clear_refs.flush();
  return static_cast<bool>(clear_refs);
}

void PhasePeaks::end(const std::string& phase) {
  peaks_.emplace_back(phase, peak_resident_bytes());
  trim_freed_memory();  // the next phase starts from what is in use (core/malloc_policy.hpp)
  separate_ = restart_peak_resident() && separate_;
}

}  // namespace rumble
