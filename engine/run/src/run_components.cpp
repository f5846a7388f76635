#include "run/run_components.hpp"

#include <array>

#include "core/cpu_affinity.hpp"
#include "core/errors.hpp"
#include "core/logging.hpp"

namespace rumble {
namespace {

const ComponentType& resolve(const PluginRegistry& registry, rumble_kind kind,
                             const scenario::ComponentSpec& c) {
  const ComponentType* t = registry.find(kind, c.type);
  if (t == nullptr) {
    throw ConfigError(c.pointer + "/type: unknown " + kind_name(kind) + " type '" + c.type +
                      "'; run `rumble plugins` to list the known types");
  }
  return *t;
}

std::unique_ptr<SoilInstance> make_soil(const scenario::ComponentSpec& c,
                                        const PluginRegistry& registry,
                                        const std::filesystem::path& dir,
                                        const std::vector<rumble_footprint>& layout,
                                        BuiltSoils* built) {
  const ComponentType& type = resolve(registry, RUMBLE_KIND_SOIL, c);
  if (built != nullptr) return built->take_or_lay(type, c.pointer, c.params, dir, layout);
  return lay_soil(type, c.pointer, c.params, dir, layout);
}

ReceiverSetup attach_receivers(SoilInstance& soil, const scenario::RunSpec& spec) {
  ReceiverSetup setup;
  const auto& receivers = spec.outputs.receivers;
  if (receivers.empty()) return setup;
  std::vector<rumble_probe> probes;
  for (const auto& r : receivers) probes.push_back({r.name.c_str(), r.x, r.y, r.depth});
  setup.probes = soil.set_probes(probes, spec.outputs.receiver_interval);
  if (!setup.probes) {
    std::vector<rumble_receiver> points;
    for (const auto& r : receivers) {
      if (r.depth == 0.0 && r.x == spec.track_middle()) {
        points.push_back({r.x, r.y});
        setup.distances.push_back(r.y);
      }
    }
    setup.surface = !points.empty() && soil.set_receivers(points);
  }
  if (!setup.probes && !setup.surface) {
    logger("engine")->warn(
        "/outputs/receivers: soil type '{}' offers no receivers; the receivers are ignored "
        "(footprint motions are still recorded)",
        soil.type_name());
  }
  return setup;
}

}  // namespace

std::vector<Instance*> RunComponents::instances() const {
  std::vector<Instance*> all{soil.get()};
  for (const auto& [name, extra] : extras) all.push_back(extra.get());
  all.push_back(coupler.get());
  for (const auto& v : track->vehicles().vehicles()) all.push_back(v.instance.get());
  return all;
}

RunComponents build_components(const scenario::RunSpec& spec, const PluginRegistry& registry,
                               BuiltSoils* built) {
  const std::filesystem::path dir = spec.path.parent_path();
  RunComponents c;
  VehicleSet vehicles;
  for (const scenario::VehicleSpec& v : spec.vehicles) {
    vehicles.add(
        std::make_unique<VehicleInstance>(resolve(registry, RUMBLE_KIND_VEHICLE, v.component),
                                          v.component.pointer, v.component.params, dir),
        v.name, v.speed, v.start);
  }
  c.track = std::make_unique<TrackParticipant>(spec.track, std::move(vehicles));
  const std::vector<rumble_footprint> layout = c.track->footprints();
  c.soil = make_soil(spec.soil, registry, dir, layout, built);
  c.coupler =
      std::make_unique<CouplerInstance>(resolve(registry, RUMBLE_KIND_COUPLER, spec.coupling),
                                        spec.coupling.pointer, spec.coupling.params, dir);
  for (const auto& [name, component] : spec.participants)
    c.extras.emplace_back(name, make_soil(component, registry, dir, layout, built));
  c.receivers = attach_receivers(*c.soil, spec);
  return c;
}

void give_run_context(RunComponents& c, const std::filesystem::path& results_dir) {
  // The statics and the soil's set-up run one participant at a time: every core is the soil's.
  // The time stepping shares them by what the coupler does (run/core_share.hpp).
  const auto soil_threads = static_cast<unsigned>(usable_cpus());
  c.soil->set_run_context(results_dir, soil_threads);
  for (auto& [name, extra] : c.extras) extra->set_run_context(results_dir, soil_threads);
  c.coupler->set_run_context(results_dir, 1);
  for (const auto& v : c.track->vehicles().vehicles())  // integrated by the engine: one thread
    v.instance->set_run_context(results_dir, 1);
}

void finalize_components(RunComponents& c) {
  c.coupler->finalize();
  c.soil->finalize();
  for (auto& [name, extra] : c.extras) extra->finalize();
  for (const auto& v : c.track->vehicles().vehicles()) v.instance->finalize();
}

std::unique_ptr<IntegratedSoil> linear_soil(SoilInstance& soil, const std::string& purpose) {
  std::array<Eigen::SparseMatrix<double>, 4> m;  // M, C, K, B (rumble_matrix order)
  for (std::size_t which = 0; which < m.size(); ++which) {
    if (!soil.linear_matrix(static_cast<rumble_matrix>(which), m[which])) {
      throw ConfigError("/soil/type: soil type '" + soil.type_name() +
                        "' gives no linear matrices, which " + purpose +
                        " needs; choose a soil that offers them (winkler, clm; rumble plugins)");
    }
  }
  return std::make_unique<IntegratedSoil>(soil.type_name(), m[0], m[1], m[2], m[3]);
}

}  // namespace rumble
