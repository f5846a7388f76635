// What the fuzz targets' checks share (docs/fuzzing.md): the per-process scratch directory of the
// targets whose readers take paths, small file helpers, and the properties every list of
// diagnostics must have, whatever the input.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "scenario/diagnostic.hpp"

namespace rumble::scenario {
struct Document;
}

namespace rumble::fuzz {

/// The source tree (the base scenarios the checks vary are read from it).
std::filesystem::path source_dir();

/// An empty directory of this process for `name` (made on first use under $TMPDIR, which
/// run_fuzzer.sh points into the test's scratch directory), removed at exit: libFuzzer runs one
/// input at a time, so each check owns its directory for the whole input.
const std::filesystem::path& scratch_dir(const std::string& name);

std::string read_file(const std::filesystem::path& path);
void write_file(const std::filesystem::path& path, std::string_view bytes);

/// Every entry under dir with its type, size and modification time, one per line, sorted: equal
/// before and after a check when nothing was written there.
std::string tree_listing(const std::filesystem::path& dir);

/// "" when every diagnostic has a message, a line inside `text` (or none: about the whole file)
/// and a column only with a line; else what is wrong.
std::string check_diagnostics(std::string_view text,
                              const std::vector<scenario::Diagnostic>& diagnostics);

/// "" when both report formats print and the JSON one parses back with every diagnostic.
std::string check_reports(const scenario::Document* doc, const std::filesystem::path& file,
                          const std::vector<scenario::Diagnostic>& diagnostics);

}  // namespace rumble::fuzz
