// The engine's own JSON Schema (draft 7) of a scenario file, the machine-readable form of
// docs/scenario.md: every key, its unit (in the description), rule, default and the unevenness
// variants. Component params are left open here; each plugin's schema checks its own.
#pragma once

#include <string_view>

namespace rumble::scenario {

/// The schema text; `rumble schema` may print it and editors may use it for completion.
std::string_view scenario_schema_text();

}  // namespace rumble::scenario
