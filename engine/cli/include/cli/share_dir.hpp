// Where the engine's run-time data lives (plot scripts, plugin templates): share/rumble next to
// the bin/ holding the executable. The build tree mirrors that layout, so the one relative
// lookup works there and in any install prefix, and no source path is compiled in.
#pragma once

#include <filesystem>

namespace rumble::cli {

/// <dir of the running executable>/../share/rumble, normalised; it may not exist.
std::filesystem::path share_directory();

}  // namespace rumble::cli
