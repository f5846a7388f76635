// Turns nlohmann's parse errors into plain words at the right line:col: "trailing comma after
// the last member of an object", "string is missing its closing quote", ...
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

#include "scenario/diagnostic.hpp"

namespace rumble::scenario {

/// `byte` and `what` are nlohmann::json::parse_error's byte position and message.
Diagnostic describe_parse_error(std::string_view text, std::size_t byte, std::string_view what);

/// nlohmann reports a number too large for a double (out_of_range 406) without a position.
Diagnostic describe_number_overflow(std::string_view text, std::string_view what);

/// Where the nesting first exceeds `max_depth` (string-aware bracket count); nullopt if never.
std::optional<std::size_t> find_excess_nesting(std::string_view text, std::size_t max_depth);

}  // namespace rumble::scenario
