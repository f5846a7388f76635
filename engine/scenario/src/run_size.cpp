#include "scenario/run_size.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/number_text.hpp"

namespace rumble::scenario {
namespace {

using nlohmann::json;

// Values per vehicle in the track's histories (wheel forces and DOFs): an estimate, the vehicle
// plugins are not asked (validate --no-load estimates too).
constexpr double kValuesPerVehicle = 10.0;
constexpr double kInterfaceColumns = 7.0;  // interface.csv: t, residual, power, energies, ...

/// "3.4 GiB", "120 MiB", "5 KiB" (binary units, as the limits are stated).
std::string bytes_text(double bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (bytes >= 1024.0 && u < 6) {
    bytes /= 1024.0;
    ++u;
  }
  char buf[48];
  const char* format = bytes < 10.0 && u > 0 ? "%.1f %s" : (bytes < 1e4 ? "%.0f %s" : "%.3g %s");
  std::snprintf(buf, sizeof buf, format, bytes, units[u]);
  return buf;
}

const char* const kConfirm = "if this run is meant, confirm it with --yes";

}  // namespace

RunSize estimate_run_size(const json& sc) {
  RunSize r;
  const double t_end = sc.at("time").at("end").get<double>();
  const double H = sc.at("time").at("macro_step").get<double>();
  r.macro_steps = std::ceil(t_end / H);
  const json& track = sc.at("track");
  if (const auto it = track.find("integrator"); it != track.end() && it->contains("micro_step"))
    r.micro_steps = std::ceil(t_end / it->at("micro_step").get<double>());
  const json& outputs = sc.at("outputs");
  const double every = outputs.at("every").get<double>();
  r.records = std::floor(r.macro_steps / every) + 1.0;

  const double footprints = track.at("sleepers").at("count").get<double>();
  const double vehicles = static_cast<double>(sc.at("vehicles").size());
  const double receivers = static_cast<double>(outputs.value("receivers", json::array()).size());
  const json& coupling = sc.at("coupling");
  const double extras = static_cast<double>(coupling.value("participants", json::object()).size());
  // contact.csv + vehicles.csv, footprint force/displacement/velocity, interface.csv,
  // receivers.csv, and each extra soil's displacement and velocity; a time column in each.
  r.values_per_record = (2.0 + vehicles * kValuesPerVehicle) + 3.0 * (footprints + 1.0) +
                        kInterfaceColumns + extras * 2.0 * (footprints + 1.0);
  // receivers.csv: a row per sample with 6 values per receiver (rumble/abi.h probes), sampled
  // every receiver_interval, else inside every soil step: at least once a macro step (the run
  // checks the soil's own rate at its first step: run/probe_recorder.hpp).
  const double interval = outputs.at("receiver_interval").get<double>();
  r.receiver_rows =
      receivers == 0.0 ? 0.0 : (interval > 0.0 ? std::floor(t_end / interval) + 1.0 : r.records);
  r.bytes_written = (r.records * r.values_per_record +
                     r.receiver_rows * (receivers > 0.0 ? 6.0 * receivers + 1.0 : 0.0)) *
                    kBytesPerValue;

  // The recorder keeps one energy per record; two_step keeps the track's footprint forces and
  // the reduced soil's motion over the whole run: 3 n (steps + 1) doubles (plugins/couplers).
  r.memory_bytes = r.records * 8.0;
  if (coupling.at("type") == "two_step")
    r.memory_bytes += 3.0 * footprints * (r.macro_steps + 1.0) * 8.0;

  r.statics_bytes = kStaticsBytesPerPair * footprints * footprints;
  if (const auto f = outputs.find("fields"); f != outputs.end() && f->contains("interval"))
    r.field_snapshots = std::floor(t_end / f->at("interval").get<double>()) + 1.0;
  return r;
}

std::vector<Diagnostic> check_run_size(const json& sc) {
  std::vector<Diagnostic> out;
  const RunSize r = estimate_run_size(sc);
  const double t_end = sc.at("time").at("end").get<double>();
  const double H = sc.at("time").at("macro_step").get<double>();
  if (r.macro_steps > kMaxMacroSteps) {
    out.push_back(finding("/time/macro_step",
                          "the run takes " + number_text(r.macro_steps) +
                              " macro steps (time.end " + number_text(t_end) + " s / macro_step " +
                              number_text(H) + " s), more than the limit of " +
                              number_text(kMaxMacroSteps),
                          std::string("raise time.macro_step or shorten time.end; ") + kConfirm));
  }
  if (r.micro_steps > kMaxMicroSteps) {
    out.push_back(finding("/track/integrator/micro_step",
                          "the track takes " + number_text(r.micro_steps) +
                              " micro-steps over the run (time.end / micro_step), more than the "
                              "limit of " +
                              number_text(kMaxMicroSteps),
                          std::string("raise micro_step, or leave it out to have it chosen from "
                                      "the contact stiffness; ") +
                              kConfirm));
  }
  if (r.bytes_written > kMaxBytesWritten) {
    out.push_back(finding("/outputs/every",
                          "the time histories would take about " + bytes_text(r.bytes_written) +
                              " on disk (" + number_text(r.records) + " records of about " +
                              number_text(r.values_per_record) + " numbers), more than the " +
                              "limit of " + bytes_text(kMaxBytesWritten),
                          std::string("record every n-th macro step (outputs.every), shorten "
                                      "time.end or raise time.macro_step; ") +
                              kConfirm));
  }
  if (r.memory_bytes > kMaxMemoryBytes) {
    const bool two_step = sc.at("coupling").at("type") == "two_step";
    out.push_back(finding(two_step ? "/coupling/type" : "/time/end",
                          "the run would reserve about " + bytes_text(r.memory_bytes) +
                              " of memory for its histories" +
                              (two_step ? " (two_step keeps every macro step's footprint forces "
                                          "and motion)"
                                        : std::string()) +
                              ", more than the limit of " + bytes_text(kMaxMemoryBytes),
                          std::string("shorten time.end, raise time.macro_step") +
                              (two_step ? " or use fewer sleepers; " : "; ") + kConfirm));
  }
  if (r.statics_bytes > kMaxMemoryBytes) {
    const double footprints = sc.at("track").at("sleepers").at("count").get<double>();
    out.push_back(finding(
        "/track/sleepers/count",
        "the static state of " + number_text(footprints) + " sleepers needs about " +
            bytes_text(r.statics_bytes) + " of memory (dense " + number_text(footprints) + " x " +
            number_text(footprints) +
            " matrices of the track/soil interface), more than the "
            "limit of " +
            bytes_text(kMaxMemoryBytes),
        "use at most " +
            number_text(std::floor(std::sqrt(kMaxMemoryBytes / kStaticsBytesPerPair))) +
            " sleepers (the track beyond a few hundred metres of the receivers barely changes "
            "their vibration); " +
            kConfirm));
  }
  if (r.field_snapshots > kMaxFieldSnapshots) {
    out.push_back(finding("/outputs/fields/interval",
                          "the run writes " + number_text(r.field_snapshots) +
                              " field snapshots (time.end / interval + 1), more than the limit "
                              "of " +
                              number_text(kMaxFieldSnapshots),
                          std::string("raise outputs.fields.interval; ") + kConfirm));
  }
  return out;
}

std::vector<Diagnostic> check_machine_room(const json& sc, const MachineRoom& room) {
  std::vector<Diagnostic> out;
  const RunSize r = estimate_run_size(sc);
  const double memory = r.statics_bytes + r.memory_bytes;
  if (memory > room.memory_bytes) {
    const bool statics = r.statics_bytes >= r.memory_bytes;
    const bool two_step = sc.at("coupling").at("type") == "two_step";
    const double sleepers = sc.at("track").at("sleepers").at("count").get<double>();
    const char* pointer =
        statics ? "/track/sleepers/count" : (two_step ? "/coupling/type" : "/time/end");
    // What fits: the statics grow as n^2 (kStaticsBytesPerPair), the histories as time.end.
    const std::string fix =
        statics
            ? "use at most " +
                  number_text(std::floor(std::sqrt(
                      std::max(0.0, room.memory_bytes - r.memory_bytes) / kStaticsBytesPerPair))) +
                  " sleepers, or free memory (other processes) and run again"
            : std::string("shorten time.end or raise time.macro_step") +
                  (two_step ? ", or use fewer sleepers" : "") +
                  "; or free memory (other processes) and run again";
    out.push_back(finding(pointer,
                          "the run needs about " + bytes_text(memory) + " of memory (" +
                              bytes_text(r.statics_bytes) + " for the static state of " +
                              number_text(sleepers) + " sleepers, " + bytes_text(r.memory_bytes) +
                              " for its histories), more than the " +
                              bytes_text(room.memory_bytes) +
                              " this machine has available now (MemAvailable, or the cgroup's "
                              "limit); --yes does not waive this",
                          fix));
  }
  if (r.bytes_written > room.disk_bytes) {
    out.push_back(finding("/outputs/every",
                          "the time histories would take at least " + bytes_text(r.bytes_written) +
                              " on disk, more than the " + bytes_text(room.disk_bytes) +
                              " free under " + room.results + " now; --yes does not waive this",
                          "record every n-th macro step (outputs.every), shorten time.end, "
                          "choose another results directory (--output DIR) or free space there"));
  }
  return out;
}

}  // namespace rumble::scenario
