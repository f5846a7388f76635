// SPDX-License-Identifier: MIT
// rumble/params_file.hpp: a file that a component's params name (an mbs vehicle's definition, a
// FEM soil's mesh), found relative to the scenario file's directory and checked before anything
// reads it: it exists, it is a regular file (a FIFO would block a reader, /dev/zero would never
// end), and it is not larger than the component will read. C++17 standard library only.
#ifndef RUMBLE_PARAMS_FILE_HPP
#define RUMBLE_PARAMS_FILE_HPP

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

namespace rumble {

/// What the file should be, for the messages.
struct ParamsFileKind {
  std::string noun = "a file";       // "a vehicle definition"
  std::string file_noun = "a file";  // "a vehicle definition file (JSON)"
  std::uintmax_t max_bytes = 0;      // larger files are refused unread
  std::string too_large_fix = "is this the right file?";
};

/// The path of the file the params name: `name` as written (`shown`: as the user wrote it, e.g.
/// the JSON string with its quotes), relative to `scenario_dir` ("" is the current directory)
/// unless absolute. Throws std::invalid_argument "<where>: <what>, got <shown>; <fix>" when it
/// does not exist, is no regular file, or is larger than kind.max_bytes.
inline std::filesystem::path checked_params_file(const std::string& where, const std::string& name,
                                                 const std::string& shown,
                                                 const std::string& scenario_dir,
                                                 const ParamsFileKind& kind) {
  namespace fs = std::filesystem;
  const std::string dir = scenario_dir.empty() ? "." : scenario_dir;
  fs::path path(name);
  if (path.is_relative()) path = fs::path(dir) / path;
  const auto fail = [&](const std::string& what, const std::string& fix) {
    throw std::invalid_argument(where + ": " + what + ", got " + shown + "; " + fix);
  };
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) {
    fail("no such file \"" + path.string() + "\"",
         "give the path of " + kind.noun + " relative to the scenario file's directory (\"" + dir +
             "\")");
  }
  if (!fs::is_regular_file(status)) {
    fail("\"" + path.string() + "\" is not a regular file (a directory, device or pipe)",
         "name " + kind.file_noun);
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > kind.max_bytes) {
    fail("\"" + path.string() + "\" is too large (" + std::to_string(size) + " bytes; " +
             kind.noun + " is at most " + std::to_string(kind.max_bytes) + " bytes)",
         kind.too_large_fix);
  }
  return path;
}

}  // namespace rumble

#endif  // RUMBLE_PARAMS_FILE_HPP
