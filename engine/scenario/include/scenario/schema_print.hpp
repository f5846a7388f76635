// `rumble schema TYPE`: one component type's params as a readable table.
#pragma once

#include <iosfwd>

namespace rumble {
struct ComponentType;
}

namespace rumble::scenario {

/// Header (type, kind, plugin file, summary), then one row per param, nested objects as
/// dotted names: name, type, required, default, range or allowed values, description (with the
/// unit). With `raw_json`, only the schema itself, pretty-printed JSON (std::runtime_error when
/// the plugin's schema is not JSON).
void print_schema(std::ostream& os, const ComponentType& type, bool raw_json);

}  // namespace rumble::scenario
