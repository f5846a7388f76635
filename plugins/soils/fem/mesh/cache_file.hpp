// What the soil's on-disk caches (meshes, receptances) share: the FNV-1a hash that names and
// checks their files, checksummed binary reads and writes, and writing a file whole (to a
// partial file renamed into place, so that a reader never sees half of one).
#pragma once

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <istream>
#include <ostream>
#include <string>

namespace rumble::fem::cache {

/// FNV-1a, 64 bit: enough to tell inputs apart and to detect a damaged file.
inline std::uint64_t fnv1a(const void* data, std::size_t bytes,
                           std::uint64_t h = 1469598103934665603ull) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
  return h;
}

/// Writes n values and folds them into the checksum.
template <class T>
void put(std::ostream& out, std::uint64_t& sum, const T* data, std::size_t n) {
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(n * sizeof(T)));
  sum = fnv1a(data, n * sizeof(T), sum);
}

/// Reads n values and folds them into the checksum; false when the file ends first.
template <class T>
bool get(std::istream& in, std::uint64_t& sum, T* data, std::size_t n) {
  in.read(reinterpret_cast<char*>(data), static_cast<std::streamsize>(n * sizeof(T)));
  sum = fnv1a(data, n * sizeof(T), sum);
  return static_cast<bool>(in);
}

/// Whether the next 8 bytes are `magic`.
inline bool read_magic(std::istream& in, const char (&magic)[8]) {
  char found[8];
  return in.read(found, 8) && std::string(found, 8) == std::string(magic, 8);
}

/// Whether the next 8 bytes are the checksum `sum`.
inline bool read_checksum(std::istream& in, std::uint64_t sum) {
  std::uint64_t stored = 0;
  return in.read(reinterpret_cast<char*>(&stored), 8) && stored == sum;
}

/// Writes magic, what `body` puts (folding into the checksum) and the checksum to a partial file
/// renamed to path (directories created). False when any of it failed: a cache is an
/// optimisation, the caller carries on.
inline bool write_whole(const std::filesystem::path& path, const char (&magic)[8],
                        const std::function<void(std::ostream&, std::uint64_t&)>& body) {
  std::error_code ec;
  std::filesystem::create_directories(path.parent_path(), ec);
  const std::filesystem::path partial =
      path.string() + ".partial." + std::to_string(static_cast<long>(::getpid()));
  {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    if (!out) return false;
    out.write(magic, 8);
    std::uint64_t sum = 0;
    body(out, sum);
    out.write(reinterpret_cast<const char*>(&sum), 8);
    if (!out) {
      out.close();
      std::filesystem::remove(partial, ec);
      return false;
    }
  }
  std::filesystem::rename(partial, path, ec);
  if (ec) std::filesystem::remove(partial, ec);
  return !ec;
}

}  // namespace rumble::fem::cache
