#include "run/divergence_monitor.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "core/errors.hpp"
#include "core/logging.hpp"

namespace rumble {
namespace {

// A footprint displacement beyond this [m] is not ground vibration, whatever the policy: the
// coupled solution has blown up (typically an unstable explicit coupling with too large a step).
constexpr double kDivergedDisplacement = 1.0;
// Nor is a footprint velocity beyond this [m/s] (checked as the displacement bound is: the
// policy says whether the run stops): ground vibration from trains is mm/s to some 0.1 m/s at a
// sleeper; an unstable coupling can run away in velocity while the displacement is still within
// its bound (Jacobi at 1 ms on the soft FEM soil: 17.7 m/s at 6 mm after 0.5 s).
constexpr double kDivergedVelocity = 10.0;
// The onset: a footprint at twice its static settlement (a train alone rarely gets there).
constexpr double kOnsetFactor = 2.0;
// A largest static footprint displacement below this [m] is no static load (a coupler that
// prescribes the forces, a vehicle weighing next to nothing): nothing to scale the size bound
// by. A train's wheel settles a footprint by 10 um or more even on the stiffest soil the docs
// treat (50 kN on 750 MPa: docs/physics.md section 6.1's K_z = 1.08e9 N/m per footprint, about
// a third of the wheel on the one below it); 1 um is 1 kN there.
constexpr double kNoStaticLoad = 1e-6;

// Two causes, told apart by the soil: a reduced soil without mass (where a shorter macro step
// makes it worse), or a macro step too long for the scheme (the paper's Jacobi at 1 ms on the
// soft soil, FEM included).
const char* const kFix =
    "If the soil is a reduced one with no participating mass (winkler `m`, clm `m_f`), give it "
    "one: a massless soil and the ballast dashpots close a loop that explicit coupling does not "
    "survive at any time.macro_step (docs/decisions/0004); otherwise (a soil with mass, fem "
    "included) reduce time.macro_step, couple with gauss_seidel rather than jacobi, or use the "
    "implicit coupler (`rumble stability FILE` gives the growth per macro step of each scheme)";

}  // namespace

std::size_t DivergenceMonitor::watch(const std::string& name, const double* u, std::size_t n) {
  double settlement = 0.0;
  for (std::size_t i = 0; i < n; ++i) settlement = std::max(settlement, std::abs(u[i]));
  const bool scaled = settlement >= kNoStaticLoad;
  if (!scaled) {
    logger("engine")->info(
        "{}: largest static footprint displacement {:.3g} m, below {:.0e} m: no static load to "
        "scale the divergence bound by (displacement_factor); the growth of the footprint "
        "speeds and the limits of {} m and {} m/s watch it",
        name, settlement, kNoStaticLoad, kDivergedDisplacement, kDivergedVelocity);
  }
  watched_.push_back({name,
                      settlement,
                      scaled ? policy_.displacement_factor * settlement : kNever,
                      std::vector<double>(u, u + n),
                      std::vector<double>(n, 0.0),
                      std::vector<double>(n, 0.0),
                      {},
                      {}});
  return watched_.size() - 1;
}

void DivergenceMonitor::watch_growth(Watched& w, const double* u, const double* v, std::size_t n,
                                     double t, double H) {
  double speed = 0.0, alternating = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double rate = (u[i] - w.u[i]) / H;  // m/s, the footprint's mean velocity over the step
    speed = std::max({speed, std::abs(v[i]), std::abs(rate)});
    alternating =
        std::max({alternating, 0.5 * std::abs(rate - w.rate[i]), 0.5 * std::abs(v[i] - w.v[i])});
    w.u[i] = u[i];
    w.v[i] = v[i];
    w.rate[i] = rate;
  }
  w.growing = w.growth.add(t, H, speed, alternating);
}

void DivergenceMonitor::diverged(std::ostringstream& m, bool stop_anyway, double t) {
  m << ". " << kFix;
  t_detected_ = std::min(t_detected_, t);
  if (stop_anyway || policy_.stop) {
    if (!stop_anyway)
      m << ". To record such a run to its end, set /coupling/divergence/action to \"continue\"";
    throw RunError(m.str());
  }
  logger("engine")->warn("{}. The run goes on (/coupling/divergence/action is \"continue\")",
                         m.str());
}

void DivergenceMonitor::check(std::size_t participant, const double* u, const double* v,
                              std::size_t n, double t, double H) {
  Watched& w = watched_[participant];
  std::size_t worst = 0, fastest = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(u[i])) {
      worst = i;
      break;
    }
    if (std::abs(u[i]) > std::abs(u[worst])) worst = i;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) {
      fastest = i;
      break;
    }
    if (std::abs(v[i]) > std::abs(v[fastest])) fastest = i;
  }
  const double u_worst = u[worst], v_fastest = v[fastest];
  const double bound = w.bound;
  if (w.bound < kNever && std::isfinite(u_worst) && std::abs(u_worst) > kOnsetFactor * w.settlement)
    t_onset_ = std::min(t_onset_, t);
  watch_growth(w, u, v, n, t, H);
  if (const std::optional<Growth>& growth = w.growing; growth && !detected()) {
    growth_ = growth;
    std::ostringstream m;
    m << "simulation diverged at t = " << t << " s: " << w.name
      << " footprint speeds grow exponentially, by " << std::setprecision(4) << growth->per_step
      << " per macro step (doubling every " << std::setprecision(3) << 1e3 * growth->doubling_s
      << " ms since t = " << growth->since_s << " s), to " << growth->peak
      << " m/s, beyond twice anything before (" << growth->peak_before
      << " m/s): an unstable coupling, not the train";
    diverged(m, false, t);
    return;
  }
  const bool too_fast = std::isfinite(v_fastest) && std::abs(v_fastest) > kDivergedVelocity;
  if (!std::isfinite(v_fastest) ||
      (too_fast && std::isfinite(u_worst) && std::abs(u_worst) <= bound && !detected())) {
    std::ostringstream m;
    m << "simulation diverged at t = " << t << " s: " << w.name << " footprint " << fastest
      << " velocity is " << v_fastest << " m/s";
    if (too_fast) m << ", more than " << kDivergedVelocity << " m/s";
    if (t_onset_ < kNever)
      m << "; a footprint first passed " << kOnsetFactor
        << " x its static displacement at t = " << t_onset_ << " s";
    diverged(m, !std::isfinite(v_fastest), t);
    return;
  }
  const bool hard = !std::isfinite(u_worst) || std::abs(u_worst) > kDivergedDisplacement;
  if (!hard && (std::abs(u_worst) <= bound || detected())) return;

  std::ostringstream m;
  m << "simulation diverged at t = " << t << " s: " << w.name << " footprint " << worst
    << " displacement is " << u_worst << " m";
  if (hard)
    m << " (limit " << kDivergedDisplacement << " m)";
  else
    m << ", more than " << policy_.displacement_factor << " x its largest static displacement ("
      << w.settlement << " m)";
  if (t_onset_ < kNever)
    m << "; it first passed " << kOnsetFactor << " x at t = " << t_onset_ << " s";
  diverged(m, hard, t);
}

nlohmann::json DivergenceMonitor::summary() const {
  const auto time = [](double t) { return t < kNever ? nlohmann::json(t) : nlohmann::json(); };
  return {{"action", policy_.stop ? "stop" : "continue"},
          {"displacement_factor", policy_.displacement_factor},
          {"detected", detected()},
          {"displacement_bound_m", watched_.empty() || !(watched_.front().bound < kNever)
                                       ? nlohmann::json()
                                       : nlohmann::json(watched_.front().bound)},
          {"t_detected_s", time(t_detected_)},
          {"t_first_beyond_twice_static_s", time(t_onset_)},
          {"growth_per_macro_step", growth_ ? nlohmann::json(growth_->per_step) : nlohmann::json()},
          {"doubling_time_s", growth_ ? nlohmann::json(growth_->doubling_s) : nlohmann::json()}};
}

}  // namespace rumble
