// SHA-256 (FIPS 180-4), for the keys that tell a study's up-to-date runs from the others. Small
// and dependency-free; not for secrets.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace rumble::study {

class Sha256 {
 public:
  Sha256();
  void update(std::string_view bytes);
  /// The digest as 64 lowercase hex digits; the object is spent afterwards.
  std::string hex();

 private:
  void block(const unsigned char* p);
  std::array<std::uint32_t, 8> h_;
  std::array<unsigned char, 64> buffer_{};
  std::size_t buffered_ = 0;
  std::uint64_t length_ = 0;  // bytes
};

/// SHA-256 of `bytes` as hex.
std::string sha256_hex(std::string_view bytes);

}  // namespace rumble::study
