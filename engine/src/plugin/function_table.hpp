// Checks a factory's function table at load time, so that a hand-written or foreign plugin with a
// short table or a missing required function is refused with its name, instead of crashing the
// first time the engine calls through a null pointer mid-run.
#pragma once

#include <rumble/abi.h>

#include <string>

namespace rumble {

/// "" when the table of a component of `kind` holds every ABI 1.0 function the engine calls
/// unconditionally (optional ones may be null, in the pairs abi.h defines); otherwise what is
/// wrong, e.g. "function table has no 'advance'".
std::string function_table_defect(rumble_kind kind, const void* api);

}  // namespace rumble
