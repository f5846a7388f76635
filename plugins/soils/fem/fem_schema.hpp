// The FEM soil's params schema (fem_schema.cpp): each parameter's name, type, unit, range and
// default, declared once.
#pragma once

namespace rumble::fem {

/// JSON Schema (draft 7) of the params.
const char* settings_schema();

/// mesh.export's rule: refused by the schema at /soil/params/mesh/export (its `not` says this),
/// and by read_settings when the params are read without the schema (issue 30: the plugin never
/// writes outside the results directory, whoever calls it).
inline constexpr const char* kExportRule =
    "mesh.export is written inside the run's results directory (outputs.directory, or --output "
    "DIR) and nowhere else: give a path relative to it without '..', e.g. 'soil.msh'";

}  // namespace rumble::fem
