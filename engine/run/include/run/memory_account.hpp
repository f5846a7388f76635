// The run's account of memory (issue #33): each phase's peak resident memory
// (core/peak_memory.hpp), per degree of freedom of the scenario's soil, and the soil's own
// estimate of the run's peak, asked for after its layout and logged before the statics spend it
// (ABI 1.5 size; docs/decisions/0014-abi-1-5.md). Written to summary.json's "memory" and, at
// the run's end, to the log.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>

#include "core/peak_memory.hpp"
#include "plugin/instance.hpp"

namespace rumble {

/// The soil's size (nothing when it does not say); its estimate logged when it gives one.
std::optional<SoilInstance::Size> announce_soil_size(const SoilInstance& soil);

/// summary.json's "memory": the phases' peaks, and with the soil's size the bytes per DOF and
/// the estimate against the largest peak.
nlohmann::json memory_summary(const PhasePeaks& memory,
                              const std::optional<SoilInstance::Size>& soil);

/// One line: the run's peak, each phase's bytes per DOF, the estimate against it.
void log_memory(const PhasePeaks& memory, const std::optional<SoilInstance::Size>& soil);

}  // namespace rumble
