#include "scenario/relation_checks.hpp"

#include <cmath>
#include <map>
#include <sstream>
#include <string>

#include "core/number_text.hpp"
#include "scenario/run_spec.hpp"
#include "track_spec/track_config.hpp"

namespace rumble {
namespace {

using scenario::Diagnostic;

using scenario::finding;

constexpr double kMaxSleepers = 100000;  // track.sleepers.count's maximum in the schema

/// Each name of `list` (at `pointer`) once: a second one would take the first one's CSV columns.
/// name_of(i) gives entry i's name ("": none to check).
template <class NameOf>
void check_unique_names(const nlohmann::json& list, const std::string& pointer, const char* what,
                        NameOf name_of, std::vector<Diagnostic>& out) {
  std::map<std::string, std::size_t> seen;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string name = name_of(i);
    if (name.empty()) continue;
    const auto [it, fresh] = seen.emplace(name, i);
    if (!fresh)
      out.push_back(finding(pointer + "/" + std::to_string(i),
                            std::string(what) + " name \"" + name + "\" is taken by " + pointer +
                                "/" + std::to_string(it->second),
                            std::string("give each ") + what + " its own name"));
  }
}

/// The micro-step, when given, within the macro step H [s].
void check_micro_step(const TrackConfig& track, double H, std::vector<Diagnostic>& out) {
  if (track.micro_step && *track.micro_step > H) {
    out.push_back(finding("/track/integrator/micro_step",
                          "the micro-step " + number_text(*track.micro_step) +
                              " s is longer than the macro step " + number_text(H) + " s",
                          "give a micro-step <= time.macro_step, or leave it out to have it "
                          "chosen from the contact stiffness"));
  }
}

/// A random unevenness's wavelength band (track_spec/unevenness_spec.hpp).
void check_unevenness_band(const UnevennessSpec& unevenness, std::vector<Diagnostic>& out) {
  for (const UnevennessFinding& f : band_findings(unevenness))
    out.push_back(finding("/track/unevenness/" + f.key, f.message, f.hint));
}

/// The vehicle reference must stay on the rail for the whole run (the wheels' offsets are
/// checked again once the vehicle plugins are loaded).
void check_vehicle_on_rail(const nlohmann::json& vehicle, const std::string& ptr, double t_end,
                           const TrackConfig& track, std::vector<Diagnostic>& out) {
  const double start = vehicle.at("start").get<double>();
  const double speed = vehicle.at("speed").get<double>();
  const double x_end = start + speed * t_end;
  if (start < track.rail_start() || start > track.rail_end()) {
    out.push_back(finding(ptr + "/start",
                          "the vehicle starts at x = " + number_text(start) + " m, off the rail [" +
                              number_text(track.rail_start()) + ", " +
                              number_text(track.rail_end()) + "] m",
                          "sleeper i lies at x = i * spacing; start within the track"));
  } else if (x_end > track.rail_end()) {
    // In double: a long run at speed may need more sleepers than an int counts (the hint
    // once read "use at least -2147483647 sleepers").
    const double needed =
        std::ceil((x_end + 2.0 * track.sleeper_spacing) / track.sleeper_spacing) + 1.0;
    const std::string more =
        needed <= kMaxSleepers
            ? ", or use at least " + number_text(needed, 15) + " sleepers (track.sleepers.count)"
            : " (the rail would need " + number_text(needed) + " sleepers, more than the " +
                  number_text(kMaxSleepers) + " allowed)";
    out.push_back(
        finding(ptr + "/speed",
                "at " + number_text(speed) + " m/s the vehicle reaches x = " + number_text(x_end) +
                    " m at t = " + number_text(t_end) + " s, past the end of the rail at " +
                    number_text(track.rail_end()) + " m",
                "lower time.end or the speed" + more));
  }
}

}  // namespace

std::vector<Diagnostic> check_scenario_relations(const nlohmann::json& sc) {
  std::vector<Diagnostic> out;
  const double t_end = sc.at("time").at("end").get<double>();
  const double H = sc.at("time").at("macro_step").get<double>();
  if (H > t_end) {
    out.push_back(finding("/time/macro_step",
                          "the macro step " + number_text(H) +
                              " s is longer than time.end = " + number_text(t_end) + " s",
                          "use a macro step of 1e-4 to 1e-3 s"));
  }
  const TrackConfig track = TrackConfig::from_json(sc.at("track"));
  check_micro_step(track, H, out);
  check_unevenness_band(track.unevenness, out);
  const auto& vehicles = sc.at("vehicles");
  check_unique_names(
      vehicles, "/vehicles", "vehicle",
      [&](std::size_t i) { return vehicles[i].value("name", "vehicle" + std::to_string(i)); }, out);
  if (const auto& o = sc.at("outputs"); o.contains("receivers")) {
    const auto& receivers = o.at("receivers");
    check_unique_names(
        receivers, "/outputs/receivers", "receiver",
        [&](std::size_t i) {
          return receivers[i].is_object()
                     ? receivers[i].value("name", std::string())
                     : scenario::distance_receiver_name(receivers[i].get<double>());
        },
        out);
  }
  for (std::size_t i = 0; i < vehicles.size(); ++i)
    check_vehicle_on_rail(vehicles[i], "/vehicles/" + std::to_string(i), t_end, track, out);
  return out;
}

}  // namespace rumble
