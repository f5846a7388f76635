// A file that the soil's params name for it to write (mesh.export): inside the run's results
// directory and nowhere else (issue 30, docs/fem-soil.md §2.1). Its path is relative to that
// directory without "..", checked when the params are read; the file is made there only during
// a run (the host's results_dir is "" when the soil is built by `rumble validate`), as a new
// file, through real directories: nothing standing there is followed, replaced or removed.
#pragma once

#include <filesystem>
#include <string>

namespace rumble::fem {

/// Why `relative` cannot name a file inside a results directory (it is absolute, or a part of
/// it is ".."), or "" when it can.
std::string outside_results(const std::string& relative);

/// Makes the empty file `relative` (outside_results() is "") inside `results_dir` for the
/// caller to write by its name, and returns its path: the folders on the way are made as real
/// directories, the file with O_CREAT | O_EXCL | O_NOFOLLOW. A symbolic link or a file on the
/// way, or anything already at the name (a file a previous run listed is removed by the engine
/// before the run), is refused. Throws std::runtime_error "<where>: <what>; <fix>".
std::filesystem::path new_results_file(const std::string& results_dir, const std::string& relative,
                                       const std::string& where);

}  // namespace rumble::fem
