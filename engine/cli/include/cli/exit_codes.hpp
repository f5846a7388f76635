// Process exit codes of the rumble CLI (docs/scenario.md).
#pragma once

namespace rumble::cli {

constexpr int kExitOk = 0;
constexpr int kExitConfig = 1;      // bad scenario or usage
constexpr int kExitPluginLoad = 2;  // a plugin library could not be loaded
constexpr int kExitRunFailed = 3;   // plugin error, divergence, interrupt, I/O

}  // namespace rumble::cli
