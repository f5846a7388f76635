// The cores this process may run on (its CPU affinity: taskset, a container's cpuset, or a study
// runner's share), which std::thread::hardware_concurrency() ignores. Granting more threads than
// that makes every barrier of a threaded soil wait for a descheduled thread.
#pragma once

#include <vector>

namespace rumble {

/// The CPU numbers in this process's affinity mask (all of hardware_concurrency() when the mask
/// cannot be read); never empty.
std::vector<int> usable_cpu_list();

/// How many: usable_cpu_list().size(), at least 1.
int usable_cpus();

/// Restricts the calling process (a child between fork and exec) to `cpus`; false when the
/// kernel refuses (the child then runs unrestricted).
bool restrict_to_cpus(const std::vector<int>& cpus);

/// The CPUs of share `k` of `shares` (0 <= k < shares) when `cpus` is split among that many
/// concurrent processes: every shares-th CPU from the k-th when there are enough, else the one
/// CPU k mod cpus.size() (processes then share CPUs rather than each seeing all of them).
std::vector<int> cpu_share(const std::vector<int>& cpus, int k, int shares);

}  // namespace rumble
