// Results are always written as new files (issue #8): whatever stands at the name (an old file, a
// symbolic link planted there) is removed first and never followed, and the file is opened with
// O_CREAT | O_EXCL | O_NOFOLLOW, so a link in the results directory cannot redirect a write to its
// target. Whole files (summary.json, soil.pvd) go through a temporary file renamed over the name,
// so a reader never sees half of one.
#pragma once

#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>

namespace rumble {

/// Removes whatever is at `path` unless it is a directory (a link is removed, not followed) and
/// opens it as a new file for writing. Returns the descriptor (close-on-exec); throws RunError
/// naming the file, the system's reason and a fix.
int open_new_file(const std::filesystem::path& path);

/// Writes `text` into the new file `tmp` and renames it over `path`. Throws RunError.
void replace_file(const std::filesystem::path& path, const std::filesystem::path& tmp,
                  std::string_view text);

/// The same without allocating and without throwing (for summary.json's heartbeat): the pieces
/// are written one after the other. Returns 0, or the errno of the step that failed.
int replace_file_noexcept(const char* path, const char* tmp,
                          std::initializer_list<std::string_view> pieces) noexcept;

/// What stands at `path`, not followed, for messages: "a symbolic link (to TARGET)", "a
/// directory", "a file", "a device, pipe or socket"; "" when nothing does.
std::string what_stands_at(const std::filesystem::path& path);

/// "cannot write results file PATH: REASON; FIX" for errno `err` (a full disk, a file size
/// limit, or a directory that refuses the write).
std::string write_error(const std::filesystem::path& path, int err);

}  // namespace rumble
