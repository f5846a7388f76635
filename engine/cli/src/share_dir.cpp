#include "cli/share_dir.hpp"

#include <boost/dll/runtime_symbol_info.hpp>

namespace rumble::cli {

std::filesystem::path share_directory() {
  const std::filesystem::path exe_dir = boost::dll::program_location().parent_path();
  return (exe_dir.parent_path() / "share" / "rumble").lexically_normal();
}

}  // namespace rumble::cli
