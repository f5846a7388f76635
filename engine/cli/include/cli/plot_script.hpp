// Runs one of the project's plotting scripts (tools/*.py, copied to share/rumble by the build and
// the install; system python3 + matplotlib) on a results directory. Plots are a convenience: a
// missing interpreter or library is a warning.
#pragma once

#include <filesystem>
#include <string>

namespace rumble::cli {

/// Returns true when the script ran and succeeded.
bool run_plot_script(const std::string& script, const std::filesystem::path& directory);

}  // namespace rumble::cli
