// SPDX-License-Identifier: MIT
// rumble/host_resources.hpp: what this machine has free now, so that a plugin (and the host)
// can refuse a size before it is spent rather than end in std::bad_alloc, the kernel's OOM
// killer or a full disk half-way through a run (docs/plugin-guide.md, "Sizes"). Header-only,
// C++17, standard library and POSIX only. SDK 1.3.
//
// Both are estimates of the moment: other processes take and give back memory and disk. Refuse
// only what clearly cannot fit, with the estimate, what is free and the parameter to change.
#ifndef RUMBLE_HOST_RESOURCES_HPP
#define RUMBLE_HOST_RESOURCES_HPP

#include <sys/statvfs.h>

#include <algorithm>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

namespace rumble {

namespace host_resources_detail {

/// The number after `key` in /proc/meminfo, in bytes (the file gives kB); -1 when absent.
inline double meminfo_bytes(const char* key) {
  std::ifstream in("/proc/meminfo");
  std::string line;
  const std::string prefix = std::string(key) + ':';
  while (std::getline(in, line)) {
    if (line.compare(0, prefix.size(), prefix) != 0) continue;
    std::istringstream value(line.substr(prefix.size()));
    double kib = -1.0;
    value >> kib;
    return kib >= 0.0 ? kib * 1024.0 : -1.0;
  }
  return -1.0;
}

/// A cgroup v2 file's number; -1 when absent or "max" (no limit).
inline double cgroup_number(const std::string& file) {
  std::ifstream in(file);
  std::string text;
  if (!(in >> text) || text == "max") return -1.0;
  try {
    return std::stod(text);
  } catch (...) {
    return -1.0;
  }
}

/// What the process's cgroup (v2: a container's or a job scheduler's limit) still allows:
/// memory.max - memory.current of its own group, or of the root seen in a container; -1 when
/// it sets no limit.
inline double cgroup_headroom_bytes() {
  std::ifstream self("/proc/self/cgroup");
  std::string line, group;
  while (std::getline(self, line))
    if (line.compare(0, 3, "0::") == 0) group = line.substr(3);
  for (const std::string& dir : {"/sys/fs/cgroup" + group, std::string("/sys/fs/cgroup")}) {
    const double max = cgroup_number(dir + "/memory.max");
    const double current = cgroup_number(dir + "/memory.current");
    if (max >= 0.0 && current >= 0.0) return std::max(0.0, max - current);
  }
  return -1.0;
}

}  // namespace host_resources_detail

/// Bytes of memory that new allocations can take without swapping: Linux's MemAvailable (free
/// memory plus the caches it can reclaim), capped by what the process's cgroup still allows;
/// infinity where neither can be read (not Linux).
inline double available_memory_bytes() {
  double bytes = std::numeric_limits<double>::infinity();
  if (const double m = host_resources_detail::meminfo_bytes("MemAvailable"); m >= 0.0) bytes = m;
  if (const double c = host_resources_detail::cgroup_headroom_bytes(); c >= 0.0)
    bytes = std::min(bytes, c);
  return bytes;
}

/// Bytes an unprivileged user may still write on the file system that holds `path`, or its
/// nearest existing parent when `path` does not exist yet (statvfs: f_bavail x f_frsize);
/// infinity when that cannot be asked, or for a file system with no blocks at all (/proc,
/// /sys: whether anything can be written there is for the write to say).
inline double free_disk_bytes(std::string path) {
  if (path.empty()) path = ".";
  for (;;) {
    struct statvfs fs {};
    if (::statvfs(path.c_str(), &fs) == 0) {
      if (fs.f_blocks == 0) break;
      return static_cast<double>(fs.f_bavail) * static_cast<double>(fs.f_frsize);
    }
    if (path == "/" || path == ".") break;
    while (path.size() > 1 && path.back() == '/') path.pop_back();
    const std::size_t slash = path.rfind('/');
    path = slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace rumble

#endif  // RUMBLE_HOST_RESOURCES_HPP
