// The engine's own JSON Schema (draft 7) of a scenario file, the machine-readable form of
// docs/scenario.md: every key, its unit (in the description), rule, default and the unevenness
// variants. Component params are left open here; each plugin's schema checks its own.
#pragma once

#include <nlohmann/json.hpp>
#include <string_view>

namespace rumble::scenario {

class SchemaChecker;

/// The schema text; `rumble schema` may print it and editors may use it for completion.
std::string_view scenario_schema_text();

/// The schema, compiled once per process.
const SchemaChecker& engine_checker();

/// `track` (a scenario's /track object) with every default the schema declares filled in, as
/// validation fills a scenario's: how a track written by hand (a test, a benchmark) gets the
/// values that the schema alone declares.
nlohmann::json track_with_defaults(nlohmann::json track);
/// The same for a /track/unevenness object.
nlohmann::json unevenness_with_defaults(nlohmann::json unevenness);

}  // namespace rumble::scenario
