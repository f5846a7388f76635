// Checks a factory's function table at load time against what the ABI minor the plugin was built
// for has (with plugin/abi_adapter.hpp, the only place that tells the minors apart), so that a
// hand-written or foreign plugin with a short table or a missing required function is refused
// with its name, instead of crashing the first time the engine calls through a null pointer.
#pragma once

#include <rumble/abi.h>

#include <cstdint>
#include <string>

namespace rumble {

/// "" when the table of a component of `kind`, from a plugin built for ABI 1.`abi_minor`, is as
/// long as that minor's table (never this host's sizeof: a 1.0 table is shorter than a 1.1 one)
/// and holds every function the engine calls unconditionally (optional ones may be null, in the
/// pairs abi.h defines); otherwise what is wrong, e.g. "function table has no 'advance'".
std::string function_table_defect(rumble_kind kind, const void* api, std::uint32_t abi_minor);

/// "" when a factory's size and capabilities record hold what ABI 1.`abi_minor` has, and every
/// capability declared has its functions (declared_functions_defect); else what is wrong.
std::string factory_capabilities_defect(const rumble_factory& f, std::uint32_t abi_minor);

/// "" when every capability a 1.1 factory declares (offers, RUMBLE_CAP_* bits) has the functions
/// the host then calls; otherwise what is missing, e.g. "declares receivers but its function
/// table has no 'set_probes'".
std::string declared_functions_defect(rumble_kind kind, const void* api, std::uint64_t offers);

}  // namespace rumble
