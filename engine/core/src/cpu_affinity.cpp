#include "core/cpu_affinity.hpp"

#include <sched.h>

#include <algorithm>
#include <thread>

namespace rumble {

std::vector<int> usable_cpu_list() {
  std::vector<int> cpus;
  cpu_set_t set;
  CPU_ZERO(&set);
  if (::sched_getaffinity(0, sizeof set, &set) == 0) {
    for (int c = 0; c < CPU_SETSIZE; ++c)
      if (CPU_ISSET(c, &set)) cpus.push_back(c);
  }
  if (cpus.empty()) {
    const int n = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    for (int c = 0; c < n; ++c) cpus.push_back(c);
  }
  return cpus;
}

int usable_cpus() {
  return static_cast<int>(usable_cpu_list().size());
}

bool restrict_to_cpus(const std::vector<int>& cpus) {
  cpu_set_t set;
  CPU_ZERO(&set);
  for (int c : cpus)
    if (c >= 0 && c < CPU_SETSIZE) CPU_SET(c, &set);
  return CPU_COUNT(&set) > 0 && ::sched_setaffinity(0, sizeof set, &set) == 0;
}

std::vector<int> cpu_share(const std::vector<int>& cpus, int k, int shares) {
  const int n = static_cast<int>(cpus.size());
  if (n == 0 || shares <= 0) return cpus;
  if (n < shares) return {cpus[static_cast<std::size_t>(k % n)]};
  std::vector<int> share;
  for (int i = k % shares; i < n; i += shares) share.push_back(cpus[static_cast<std::size_t>(i)]);
  return share;
}

}  // namespace rumble
