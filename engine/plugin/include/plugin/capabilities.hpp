// Names of the capability bits of rumble_capabilities (abi.h), in one table: a key for JSON
// ("save_restore") and a phrase for messages ("save and restore its state").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rumble {

/// Keys of the bits set, in bit order, e.g. {"save_restore", "receivers"}.
std::vector<std::string> capability_keys(std::uint64_t bits);

/// "save and restore its state and record receivers" ("do nothing special" for 0).
std::string capability_text(std::uint64_t bits);

}  // namespace rumble
