// Matches what the scenario's components need against what they declare they offer (ABI 1.1
// capabilities), before anything runs: a coupler's soil_needs against /soil and its extra
// participants, the extra participants a coupler declares against /coupling/participants,
// each component's largest macro step against /time/macro_step, once-per-process types used
// twice, receivers asked of a soil that offers none. Each finding names its JSON pointer; the
// caller places it in the text.
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "scenario/diagnostic.hpp"

namespace rumble {
class PluginRegistry;
}

namespace rumble::scenario {

/// scenario: schema-checked, defaults filled. Components of unknown type are skipped (validate
/// has reported them).
std::vector<Diagnostic> check_capabilities(const nlohmann::json& scenario,
                                           const PluginRegistry& registry);

/// A command that reads a soil's whole operator, as its refusal on ranks names it: e.g.
/// {"rumble stability", "it linearizes the track on the soil", "linear_matrix"}. name null: none
/// (a run, whose coupler decides).
struct WholeSoilCommand {
  const char* name = nullptr;
  const char* why = nullptr;
  const char* reads = nullptr;  // the soil's function that needs the whole operator
};

/// What needs a soil's whole operator against a soil split over MPI ranks: a soil that declares
/// RUMBLE_CAP_DISTRIBUTED holds only its part on each of `ranks` > 1 ranks
/// (docs/decisions/0012-distributed-soil.md), so a monolithic coupler (/coupling/type) and a
/// command that reads the whole operator (`command`, at /soil/type) are refused before the soil
/// is built, where a FEM soil meshes. Nothing for ranks <= 1.
std::vector<Diagnostic> check_split_soil(const nlohmann::json& scenario,
                                         const PluginRegistry& registry, int ranks,
                                         const WholeSoilCommand& command = {});

}  // namespace rumble::scenario
