// mbs_schema.hpp: the JSON Schema (draft 7) of the mbs vehicle's params.
#ifndef RUMBLE_MBS_SCHEMA_HPP
#define RUMBLE_MBS_SCHEMA_HPP

namespace rumble::mbs {

const char* mbs_params_schema();

}  // namespace rumble::mbs

#endif  // RUMBLE_MBS_SCHEMA_HPP
