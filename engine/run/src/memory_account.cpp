#include "run/memory_account.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>

#include "core/logging.hpp"
#include "core/number_text.hpp"
#include "plugin/rank_memory.hpp"

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

/// Per rank (rank 0 first), its peak in each phase [bytes].
std::vector<std::vector<std::uint64_t>> by_rank(const RunMemory& memory) {
  const auto& own = memory.own().peaks();
  std::vector<std::vector<std::uint64_t>> ranks(1 + memory.others().front().size());
  for (std::size_t phase = 0; phase < own.size(); ++phase) {
    ranks[0].push_back(own[phase].second);
    for (std::size_t k = 1; k < ranks.size(); ++k)
      ranks[k].push_back(memory.others()[phase][k - 1]);
  }
  return ranks;
}

/// summary.json's memory.ranks: each phase's peak on every rank, each rank's largest, and per
/// DOF of a rank's share (the soil's DOFs over the ranks: a distributed soil's even split).
nlohmann::json ranks_summary(const RunMemory& memory,
                             const std::optional<SoilInstance::Size>& soil) {
  const std::vector<std::vector<std::uint64_t>> ranks = by_rank(memory);
  const auto& phases = memory.own().peaks();
  nlohmann::json peaks = nlohmann::json::object();
  for (std::size_t p = 0; p < phases.size(); ++p) {
    peaks[phases[p].first] = nlohmann::json::array();
    for (const auto& rank : ranks) peaks[phases[p].first].push_back(rank[p]);
  }
  nlohmann::json largest = nlohmann::json::array();
  std::uint64_t top = 0;
  for (const auto& rank : ranks) {
    const std::uint64_t bytes = *std::max_element(rank.begin(), rank.end());
    largest.push_back(bytes);
    top = std::max(top, bytes);
  }
  nlohmann::json r = {{"count", ranks.size()},
                      {"peak_resident_bytes", peaks},
                      {"run_peak_bytes", largest},
                      {"definition",
                       "each rank's peak per phase, measured on that rank at the phases' ends "
                       "(rank 0's are peak_resident_bytes above); run_peak_bytes: each rank's "
                       "largest"}};
  if (!soil || soil->dofs == 0) return r;
  const double share = static_cast<double>(soil->dofs) / static_cast<double>(ranks.size());
  nlohmann::json per_share = nlohmann::json::array();
  for (const nlohmann::json& bytes : largest) per_share.push_back(bytes.get<double>() / share);
  r["run_peak_bytes_per_dof_of_share"] = per_share;
  if (soil->peak_bytes > 0.0 && top > 0)
    r["estimate_over_largest_peak"] = soil->peak_bytes / static_cast<double>(top);
  return r;
}

/// One line: each rank's peak, its phase and, with the soil's size, its bytes per DOF of a share.
void log_ranks(const RunMemory& run, const std::optional<SoilInstance::Size>& soil) {
  const std::vector<std::vector<std::uint64_t>> ranks = by_rank(run);
  const auto& phases = run.own().peaks();
  std::ostringstream m;
  m << "peak resident memory per rank (VmHWM on each rank, each phase its own):";
  for (std::size_t k = 0; k < ranks.size(); ++k) {
    const auto top = std::max_element(ranks[k].begin(), ranks[k].end());
    m << (k == 0 ? " rank " : "; rank ") << k << ' ' << gigabytes(static_cast<double>(*top)) << " ("
      << phases[static_cast<std::size_t>(top - ranks[k].begin())].first;
    if (soil && soil->dofs > 0)
      m << ", "
        << per_dof(static_cast<double>(*top) * static_cast<double>(ranks.size()),
                   static_cast<double>(soil->dofs))
        << " per DOF of a share";
    m << ')';
  }
  logger("engine")->info("{}", m.str());
}

}  // namespace

void RunMemory::end(const std::string& phase) {
  own_.end(phase);
  if (const std::optional<ServerPeaks> servers = end_phase_on_servers()) {
    others_.push_back(servers->bytes);
    others_separate_ = others_separate_ && servers->separate;
  }
}

std::optional<SoilInstance::Size> announce_soil_size(const SoilInstance& soil) {
  std::optional<SoilInstance::Size> size = soil.size();
  if (size && size->peak_bytes > 0.0 && size->dofs > 0)
    logger("engine")->info(
        "the soil ({} DOFs) estimates the run's peak resident memory at {} ({} per DOF)",
        number_text(static_cast<double>(size->dofs), 3), gigabytes(size->peak_bytes),
        per_dof(size->peak_bytes, static_cast<double>(size->dofs)));
  return size;
}

nlohmann::json memory_summary(const RunMemory& run, const std::optional<SoilInstance::Size>& soil) {
  const PhasePeaks& memory = run.own();
  nlohmann::json peaks = nlohmann::json::object();
  for (const auto& [phase, bytes] : memory.peaks()) peaks[phase] = bytes;
  nlohmann::json m = {
      {"peak_resident_bytes", peaks},
      {"definition",
       run.separate()
           ? "each phase's own peak of the process's resident memory (VmHWM, restarted at the "
             "phase's start); build: everything before the statics, validation and the soil's "
             "meshing and assembly included; statics: up to the soils' statics_done, after which "
             "they free what only their statics needed; under mpirun, rank 0's"
           : "the process's peak resident memory from its start to each phase's end (this system "
             "does not let a process restart its peak)"}};
  if (!run.others().empty()) m["ranks"] = ranks_summary(run, soil);
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

void log_memory(const RunMemory& run, const std::optional<SoilInstance::Size>& soil) {
  const PhasePeaks& memory = run.own();
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
  if (!run.others().empty()) log_ranks(run, soil);
}

}  // namespace rumble
