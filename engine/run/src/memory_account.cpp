#include "run/memory_account.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>

#include "core/logging.hpp"
#include "core/number_text.hpp"

namespace rumble {
namespace {

/// The largest of the phases' peaks [bytes] and its phase.
std::pair<std::string, std::uint64_t> largest(const PhasePeaks& memory) {
  std::pair<std::string, std::uint64_t> top{"", 0};
  for (const auto& [phase, bytes] : memory.peaks())
    if (bytes > top.second) top = {phase, bytes};
  return top;
}

std::string gigabytes(double bytes) {
  return number_text(bytes / 1e9, 3) + " GB";
}

/// Bytes per DOF, whole.
std::string per_dof(double bytes, double dofs) {
  return std::to_string(std::lround(bytes / dofs)) + " B";
}

}  // namespace

std::optional<SoilInstance::Size> announce_soil_size(const SoilInstance& soil) {
  std::optional<SoilInstance::Size> size = soil.size();
  if (size && size->peak_bytes > 0.0 && size->dofs > 0)
    logger("engine")->info(
        "the soil ({} DOFs) estimates the run's peak resident memory at {} ({} per DOF)",
        number_text(static_cast<double>(size->dofs), 3), gigabytes(size->peak_bytes),
        per_dof(size->peak_bytes, static_cast<double>(size->dofs)));
  return size;
}

nlohmann::json memory_summary(const PhasePeaks& memory,
                              const std::optional<SoilInstance::Size>& soil) {
  nlohmann::json peaks = nlohmann::json::object();
  for (const auto& [phase, bytes] : memory.peaks()) peaks[phase] = bytes;
  nlohmann::json m = {
      {"peak_resident_bytes", peaks},
      {"definition",
       memory.separate()
           ? "each phase's own peak of the process's resident memory (VmHWM, restarted at the "
             "phase's start); build: everything before the statics, validation and the soil's "
             "meshing and assembly included; statics: up to the soils' statics_done, after which "
             "they free what only their statics needed"
           : "the process's peak resident memory from its start to each phase's end (this system "
             "does not let a process restart its peak)"}};
  if (!soil || soil->dofs == 0) return m;
  const auto dofs = static_cast<double>(soil->dofs);
  nlohmann::json per_dof = nlohmann::json::object();
  for (const auto& [phase, bytes] : memory.peaks())
    per_dof[phase] = static_cast<double>(bytes) / dofs;
  m["soil_dofs"] = soil->dofs;
  m["bytes_per_dof"] = per_dof;
  if (soil->peak_bytes > 0.0) {
    m["soil_estimate_bytes"] = soil->peak_bytes;
    if (const auto top = largest(memory); top.second > 0)
      m["estimate_over_peak"] = soil->peak_bytes / static_cast<double>(top.second);
  }
  return m;
}

void log_memory(const PhasePeaks& memory, const std::optional<SoilInstance::Size>& soil) {
  const auto [phase, peak] = largest(memory);
  if (peak == 0) return;  // (no /proc: nothing measured)
  std::ostringstream m;
  m << "peak resident memory " << gigabytes(static_cast<double>(peak)) << " (" << phase << ")";
  if (soil && soil->dofs > 0) {
    const auto dofs = static_cast<double>(soil->dofs);
    m << "; per DOF of the soil's " << number_text(dofs, 3) << ":";
    for (const auto& [name, bytes] : memory.peaks())
      m << ' ' << name << ' ' << per_dof(static_cast<double>(bytes), dofs);
    if (soil->peak_bytes > 0.0)
      m << "; the soil estimated " << gigabytes(soil->peak_bytes) << ", "
        << number_text(soil->peak_bytes / static_cast<double>(peak), 3) << " times the peak";
  }
  logger("engine")->info("{}", m.str());
}

}  // namespace rumble
