// A scenario file as read from disk: its path, its exact text (for positions) and the parsed JSON.
#pragma once

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "scenario/diagnostic.hpp"

namespace rumble::scenario {

struct Document {
  std::filesystem::path path;  // as given; relative paths inside the scenario are relative to it
  std::string text;
  nlohmann::json json;
};

/// Scenario files hold parameters, not data; anything larger is refused before it is read.
inline constexpr std::size_t kMaxDocumentBytes = std::size_t{64} << 20;
/// Deeper nesting is refused before parsing, so that no recursive consumer can overflow.
inline constexpr std::size_t kMaxNestingDepth = 256;

/// Reads and parses a scenario file. On failure returns nullopt and appends diagnostics: file
/// not found, not a regular file, not readable, empty, too large, too deeply nested, or a
/// syntax error with its line:col and a hint.
std::optional<Document> load_document(const std::filesystem::path& path,
                                      std::vector<Diagnostic>& diagnostics);

/// The same checks on text already in memory (`path` is only used in messages).
std::optional<Document> parse_document(std::filesystem::path path, std::string text,
                                       std::vector<Diagnostic>& diagnostics);

}  // namespace rumble::scenario
