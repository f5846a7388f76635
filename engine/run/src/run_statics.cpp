#include "run/run_statics.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "core/logging.hpp"

namespace rumble {
namespace {

/// The soil the track's static state is found on: the scenario's, or the coupler's extra soil
/// declared with "track_statics" (abi.h, rumble_capabilities::participants_json).
SoilInstance& static_partner(RunComponents& c) {
  const auto declared =
      nlohmann::json::parse(c.coupler->type().capabilities.participants_json, nullptr, false);
  for (auto& [name, extra] : c.extras) {
    if (declared.is_object() && declared.contains(name) && declared[name].is_object() &&
        declared[name].value("track_statics", false))
      return *extra;
  }
  return *c.soil;
}

/// The soil's own statics u against its matrices' K^-1 B F, which the monolithic soil moves
/// about (abi.h linear_matrix): a soil may hold more statically than its matrices (the FEM
/// soil's static far field, docs/fem-soil.md section 3.2: a few per cent), which is logged; one
/// whose matrices miss a tenth of its settlement does not describe itself, and is refused.
void check_integrated_statics(const SoilInstance& soil, const TrackParticipant& track,
                              const std::vector<double>& u) {
  double beyond = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    beyond = std::max(beyond, std::abs(track.integrated_static_offset(i)));
    scale = std::max(scale, std::abs(u[i]));
  }
  std::ostringstream m;
  m << "soil '" << soil.type_name() << "': its statics hold the footprints up to " << beyond
    << " m beyond its linear matrices' K^-1 B F (largest settlement " << scale << " m)";
  if (beyond > 0.1 * scale) {
    m << "; its linear_matrix does not describe it, so it cannot be integrated with the track";
    throw RunError(m.str());
  }
  if (beyond > 1e-6 * scale)
    logger("engine")->info(
        "{} (a static far field beyond the matrices); the integrated soil "
        "moves about its own static state",
        m.str());
}

/// Static equilibrium of the track and its static partner (static_partner); the other soils
/// start from the same static footprint forces. Returns the track/soil iterations.
int solve_statics(RunComponents& c) {
  SoilInstance& partner = static_partner(c);
  const int iterations =
      c.track->solve_static([&](const std::vector<double>& force, std::vector<double>& u) {
        partner.initialize(0.0, force, u);
      });
  const std::size_t n = c.track->interface_size();
  std::vector<double> force(n), u;
  c.track->footprint_forces(force.data());
  if (&partner != c.soil.get() || c.track->has_integrated_soil()) {
    c.soil->initialize(0.0, force, u);
  }
  if (c.track->has_integrated_soil()) check_integrated_statics(*c.soil, *c.track, u);
  for (auto& [name, extra] : c.extras)
    if (extra.get() != &partner) extra->initialize(0.0, force, u);
  return iterations;
}

/// solve_statics as a phase Ctrl-C can stop: a soil that honoured a stop request inside its
/// static solve (a FEM soil's take tens of seconds at a million DOFs) fails it, which is an
/// interruption, not a failure.
int solve_statics_unless_stopped(RunComponents& c, const std::filesystem::path& results_dir) {
  try {
    const StopPhase phase("the static state");
    return solve_statics(c);
  } catch (const std::exception&) {
    if (!interrupt_requested()) throw;
    throw Interrupted(std::string("interrupted (") + interrupt_cause() +
                      ") while the static state was solved, before the first step; "
                      "summary.json in " +
                      results_dir.string() + " says so");
  }
}

}  // namespace

bool integrate_soil_if_asked(RunComponents& c) {
  if (!c.coupler->type().capabilities.has(RUMBLE_CAP_MONOLITHIC)) return false;
  c.track->integrate_soil(linear_soil(*c.soil, "coupler '" + c.coupler->type_name() + "'"));
  return true;
}

StaticState static_equilibrium(RunComponents& c, const std::filesystem::path& results_dir) {
  const auto start = std::chrono::steady_clock::now();
  StaticState s;
  s.iterations = solve_statics_unless_stopped(c, results_dir);
  // The soils free what only their statics needed before the steps (ABI 1.5).
  c.soil->statics_done();
  for (auto& [name, extra] : c.extras) extra->statics_done();
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const TrackParticipant& track = *c.track;
  for (std::size_t w = 0; w < track.vehicles().wheel_count(); ++w)
    s.wheel_loads.push_back(track.contact_force(w));
  logger("engine")->info("static state: {} wheel(s), loads {} N, {} track/soil iteration(s)",
                         track.vehicles().wheel_count(), s.wheel_loads.dump(), s.iterations);
  return s;
}

}  // namespace rumble
