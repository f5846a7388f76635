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

}  // namespace

std::vector<ReceiverSpec> receivers(const json& list, double x_mid) {
  std::vector<ReceiverSpec> out;
  for (const json& r : list) {
    ReceiverSpec p;
    if (r.is_number()) {
      p.y = r.get<double>();
      p.x = x_mid;
      p.name = distance_receiver_name(p.y);
    } else {
      p.name = r.at("name").get<std::string>();
      p.y = r.at("y").get<double>();
      p.x = r.value("x", x_mid);
      p.depth = r.at("depth").get<double>();
    }
    out.push_back(std::move(p));
  }
  return out;
}

double RunSpec::track_middle() const {
  return track.middle_x();
}

std::string distance_receiver_name(double y) {
  char name[48];
  std::snprintf(name, sizeof name, "d=%g m", y);
  return name;
}

fs::path results_directory(const json& document, const fs::path& path) {
  const fs::path dir = document.at("outputs").at("directory").get<std::string>();
  return dir.is_absolute() ? dir : path.parent_path() / dir;
}

namespace {

/// `path` is `folder` or inside it (both lexically normal).
bool within(const fs::path& path, const fs::path& folder) {
  const fs::path relative = path.lexically_relative(folder);
  return !relative.empty() && *relative.begin() != "..";
}

/// Where `relative` leads from the directory `from` (canonical) once its missing directories are
/// made, as the system resolves it: each part that exists is resolved (a symbolic link followed,
/// ".." the parent of the real directory), a missing one appended as it is; `link`: the first
/// symbolic link on the way that leads out of `from`, "" when none. A link that leads nowhere
/// stays as it is (making a directory there fails). Not std::filesystem::weakly_canonical: it
/// takes the missing tail lexically, so "new/../link" would pass for "link" unresolved.
fs::path resolved(const fs::path& from, const fs::path& relative, fs::path& link) {
  fs::path at = from;
  link.clear();
  for (const fs::path& part : relative) {
    if (part.empty() || part == ".") continue;
    if (part == "..") {
      at = at.parent_path();
      continue;
    }
    at /= part;
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(at, ec))) continue;  // canonical so far
    const fs::path real = fs::canonical(at, ec);
    if (ec) continue;
    if (link.empty() && !within(real, from)) link = at;
    at = real;
  }
  return at;
}

}  // namespace

std::optional<Diagnostic> outside_folder(const ResultsFolderRule& rule, const fs::path& path,
                                         const std::string& given) {
  const fs::path file = fs::absolute(path).lexically_normal();
  const fs::path folder = file.parent_path();
  const fs::path target = (folder / given).lexically_normal();  // `given` when absolute
  const std::string quoted = json(given).dump();
  const auto refused = [&](const std::string& why, const fs::path& to) {
    return finding(rule.pointer, why,
                   "results go inside the " + rule.file +
                       "'s folder unless the command line says otherwise: " + rule.choices +
                       " to write to " + to.string());
  };
  // /dev/stdin, /proc/self/fd/N, a pipe: no folder of the file's own to stay in.
  std::error_code ec;
  const auto top = std::next(file.begin());
  if (!fs::is_regular_file(path, ec) || (top != file.end() && (*top == "dev" || *top == "proc"))) {
    return refused("the " + rule.file + " is read from " + path.string() +
                       ", not from a file in a folder, so " + quoted + " would be " +
                       target.string(),
                   target);
  }
  if (fs::path(given).is_absolute()) return refused(quoted + " is an absolute path", target);
  const fs::path relative = fs::path(given).lexically_normal();
  if (!relative.empty() && *relative.begin() == "..") {
    return refused(quoted + " leaves the " + rule.file + "'s folder " + folder.string() +
                       " (it is " + target.string() + ")",
                   target);
  }
  // Lexically inside; through the links of what exists, perhaps not.
  const fs::path real_folder = fs::canonical(folder, ec);
  if (ec) return std::nullopt;  // unreadable: making the directory will say why
  fs::path link;
  const fs::path real = resolved(real_folder, given, link);
  if (within(real, real_folder)) return std::nullopt;
  const std::string through =
      link.empty() ? "" : " through the symbolic link " + link.lexically_normal().string();
  return refused(quoted + " leads out of the " + rule.file + "'s folder " + folder.string() +
                     through + " (it is " + real.string() + ")",
                 real);
}

std::optional<Diagnostic> results_outside_scenario_folder(const json& document,
                                                          const fs::path& path) {
  return outside_folder({"/outputs/directory", "scenario",
                         "choose the directory with --output DIR, or pass --allow-outside-results"},
                        path, document.at("outputs").at("directory").get<std::string>());
}

// `document` is validated, its defaults filled: every value the schema defaults is read with at(),
// never with a fallback that would declare it a second time.
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
  const json& divergence = coupling.at("divergence");
  s.divergence.displacement_factor = divergence.at("displacement_factor").get<double>();
  s.divergence.stop = divergence.at("action").get<std::string>() == "stop";
  const json participants = coupling.value("participants", json::object());
  for (const auto& [name, c] : participants.items())
    s.participants.emplace_back(name, component(c, "/coupling/participants/" + name));
  const json& out = document.at("outputs");
  s.outputs.directory = results_directory(document, path);
  s.outputs.receivers = receivers(out.value("receivers", json::array()), s.track_middle());
  s.outputs.receiver_interval = out.at("receiver_interval").get<double>();
  if (out.contains("fields"))
    s.outputs.field_interval = out.at("fields").at("interval").get<double>();
  s.outputs.every = out.at("every").get<std::size_t>();
  s.outputs.plots = out.at("plots").get<bool>();
  return s;
}

}  // namespace rumble::scenario
