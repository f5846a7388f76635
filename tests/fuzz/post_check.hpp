// What the post fuzz target checks for one input (the files of a results directory that
// `rumble post` reads), shared by the libFuzzer target (fuzz_target.cpp, preset "fuzz") and the
// replay test of the other presets (replay_test.cpp).
#pragma once

#include <string>
#include <string_view>

namespace rumble::fuzz {

/// The line that ends receivers.csv in an input and starts its summary.json: an input is
/// receivers.csv's bytes, then optionally this line and summary.json's bytes (one file a seed,
/// readable and cut by libFuzzer like any text).
inline constexpr std::string_view kSummaryMarker = "\n=== summary.json\n";

/// Writes the input's receivers.csv (and summary.json when it has one) into an empty results
/// directory of this process and puts it through what `rumble post DIR` does with them (the
/// directory's manifest and lock aside): read_csv, then for a record of at most 1000 rows and
/// 24 columns (larger ones cost the fuzzer seconds of FFTs and CWTs, and add no branches),
/// options_from_summary and post_process. Returns "" when every property holds, else what broke:
///   - read_csv refuses with a std::runtime_error naming receivers.csv, or gives a table with a
///     time and a column per header field after the first, all of one length, no longer than the
///     lines of the file, and at most one warning (the cut last line); split_csv_line gives the
///     header's fields back from their quoted forms;
///   - post_process refuses with a std::runtime_error (what `rumble post` reports as the
///     scenario's problem, exit 1) naming the results directory, and nothing else escapes;
///   - what it writes is consistent: every file listed exists; every CSV has rows as wide as
///     its header; ppv.csv has a row per receiver with a finite distance and PPV; post.json
///     parses back with as many receivers and the samples of the record's grid.
std::string check_post_input(std::string_view input);

}  // namespace rumble::fuzz
