#include "scenario/run_spec.hpp"

#include <cstdio>
#include <iterator>

namespace rumble::scenario {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

ComponentSpec component(const json& j, std::string pointer) {
  return {std::move(pointer), j.at("type").get<std::string>(), j.value("params", json::object())};
}

std::vector<ReceiverSpec> receivers(const json& list, double x_mid) {
  std::vector<ReceiverSpec> out;
  for (const json& r : list) {
    ReceiverSpec p;
    if (r.is_number()) {
      p.y = r.get<double>();
      p.x = x_mid;
      char name[48];
      std::snprintf(name, sizeof name, "d=%g m", p.y);
      p.name = name;
    } else {
      p.name = r.at("name").get<std::string>();
      p.y = r.at("y").get<double>();
      p.x = r.value("x", x_mid);
      p.depth = r.value("depth", 0.0);
    }
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace

double RunSpec::track_middle() const {
  return 0.5 * (track.sleeper_count - 1) * track.sleeper_spacing;
}

fs::path results_directory(const json& document, const fs::path& path) {
  const fs::path dir = document.at("outputs").at("directory").get<std::string>();
  return dir.is_absolute() ? dir : path.parent_path() / dir;
}

std::optional<Diagnostic> results_outside_scenario_folder(const json& document,
                                                          const fs::path& path) {
  const std::string given = document.at("outputs").at("directory").get<std::string>();
  const fs::path file = fs::absolute(path).lexically_normal();
  const fs::path folder = file.parent_path();
  const fs::path target = (folder / given).lexically_normal();  // `given` when absolute
  const std::string quoted = json(given).dump();
  const auto refused = [&](const std::string& why) {
    return finding("/outputs/directory", why,
                   "results go inside the scenario's folder unless the command line says "
                   "otherwise: choose the directory with --output DIR, or pass "
                   "--allow-outside-results to write to " +
                       target.string());
  };
  // /dev/stdin, /proc/self/fd/N, a pipe: no folder of the scenario's own to stay in.
  std::error_code ec;
  const auto top = std::next(file.begin());
  if (!fs::is_regular_file(path, ec) || (top != file.end() && (*top == "dev" || *top == "proc"))) {
    return refused("the scenario is read from " + path.string() +
                   ", not from a file in a folder, so " + quoted + " would be " + target.string());
  }
  if (fs::path(given).is_absolute()) return refused(quoted + " is an absolute path");
  const fs::path relative = fs::path(given).lexically_normal();
  if (!relative.empty() && *relative.begin() == "..") {
    return refused(quoted + " leaves the scenario's folder " + folder.string() + " (it is " +
                   target.string() + ")");
  }
  return std::nullopt;
}

RunSpec make_run_spec(const json& document, const fs::path& path) {
  RunSpec s;
  s.path = path;
  s.document = document;
  s.t_end = document.at("time").at("end").get<double>();
  s.macro_step = document.at("time").at("macro_step").get<double>();
  const json& vehicles = document.at("vehicles");
  for (std::size_t i = 0; i < vehicles.size(); ++i) {
    const json& v = vehicles[i];
    s.vehicles.push_back({component(v, "/vehicles/" + std::to_string(i)),
                          v.value("name", "vehicle" + std::to_string(i)),
                          v.at("speed").get<double>(), v.at("start").get<double>()});
  }
  s.track = TrackConfig::from_json(document.at("track"));
  s.soil = component(document.at("soil"), "/soil");
  const json& coupling = document.at("coupling");
  s.coupling = component(coupling, "/coupling");
  const json divergence = coupling.value("divergence", json::object());
  s.divergence.displacement_factor = divergence.value("displacement_factor", 20.0);
  s.divergence.stop = divergence.value("action", std::string("stop")) == "stop";
  const json participants = coupling.value("participants", json::object());
  for (const auto& [name, c] : participants.items())
    s.participants.emplace_back(name, component(c, "/coupling/participants/" + name));
  const json& out = document.at("outputs");
  s.outputs.directory = results_directory(document, path);
  s.outputs.receivers = receivers(out.value("receivers", json::array()), s.track_middle());
  s.outputs.receiver_interval = out.value("receiver_interval", 0.0);
  if (out.contains("fields"))
    s.outputs.field_interval = out.at("fields").at("interval").get<double>();
  s.outputs.every = out.value("every", std::size_t{1});
  s.outputs.plots = out.value("plots", true);
  return s;
}

}  // namespace rumble::scenario
