// `rumble mesh FILE [--output DIR] [--allow-outside-results] [--set POINTER=VALUE ...]`: build the
// scenario's soil on the track's footprints, as a run would, without running: the soil reports its
// discretisation in the log (a FEM soil: nodes, DOFs, smallest element, stable step, frequency
// resolved at each distance) and, when it offers field output, writes it to DIR/mesh.vtu to look at
// in ParaView before spending a run on it. DIR is the soil's results directory meanwhile: a FEM
// soil's mesh.export goes there (docs/fem-soil.md §2.1). --ranks N: the soil is built on one
// process as ever, told through rumble_host.planned_ranks (ABI 1.6) that a run on N ranks is
// planned; a FEM soil then reports its estimate per rank (docs/fem-soil.md, "Planning the ranks").
#include <sys/stat.h>
#include <unistd.h>

#include <iostream>
#include <optional>
#include <string>

#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "cli/scenario_prepare.hpp"
#include "core/errors.hpp"
#include "plugin/instance.hpp"
#include "results/new_file.hpp"
#include "run/run_scenario.hpp"

namespace rumble::cli {
namespace {

/// mesh.vtu is `rumble mesh`'s own name in the directory (a run leaves it alone): a regular file
/// there, an earlier mesh, is replaced by a new one; anything else (a symbolic link, a
/// directory, a device) is left alone and refused, since the soil writes the file by its name.
void new_mesh_file(const std::filesystem::path& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    throw ConfigError(path.lexically_normal().string() + " is " + what_stands_at(path) +
                      "; rumble mesh writes mesh.vtu as a new file, never through a link nor over "
                      "anything but an earlier mesh.vtu: move it away, or choose another "
                      "directory with --output DIR");
  }
  ::close(open_new_file(path));  // whatever stood there removed, the file made anew
}

/// --ranks N: an integer from 1 to 1e6, the soil's rumble_host.planned_ranks (ABI 1.6).
void plan_ranks(const std::optional<std::string>& text) {
  set_planned_ranks(0);
  if (!text) return;
  std::size_t used = 0;
  long n = 0;
  try {
    n = std::stol(*text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text->size() || n < 1 || n > 1000000)
    throw UsageError("--ranks=" + *text +
                     " is not a number of MPI ranks; give an integer from 1 to 1000000, the N "
                     "of the planned `mpirun -n N rumble run`");
  set_planned_ranks(static_cast<int>(n));
}

}  // namespace

int mesh_command(const std::vector<std::string>& args) {
  const Arguments a(args, {"allow-outside-results"}, {"output", "ranks"}, {"set"});
  if (a.positional().size() != 1) {
    throw UsageError(
        "usage: rumble mesh FILE [--output DIR] [--ranks N] [--allow-outside-results] [--set "
        "POINTER=VALUE ...]");
  }
  plan_ranks(a.value("ranks"));                           // (before the soil is built)
  const auto output = a.directory("output", "mesh.vtu");  // before a mesh is built
  std::vector<scenario::Override> overrides;
  for (const std::string& set : a.values("set"))
    overrides.push_back(scenario::parse_set_option(set));
  PluginRegistry registry;
  BuiltSoils built;  // the soil validation builds is the one looked at: meshed once
  scenario::CheckOptions check = kNotARun;
  check_results_directory(check, output.has_value(), a.flag("allow-outside-results"));
  check.keep_soils = &built;
  const auto doc =
      prepare_scenario(a.positional().front(), registry, scenario::Format::kText, overrides, check);
  if (!doc) return kExitConfig;
  const ScenarioSoil s = soil_on_footprints(*doc, registry, &built);
  const std::filesystem::path out_dir =
      output ? std::filesystem::path(*output) : scenario::results_directory(doc->json, doc->path);
  if (!s.soil->offers_fields()) {
    std::cout << "soil type '" << s.type->type_name
              << "' offers no field output: its report above is all there is to see\n";
    return kExitOk;
  }
  std::filesystem::create_directories(out_dir);
  s.soil->set_results_dir(out_dir);  // where its own files go: a FEM soil's mesh.export
  const auto path = out_dir / "mesh.vtu";
  new_mesh_file(path);
  try {
    s.soil->write_fields(0.0, path);
  } catch (...) {
    std::filesystem::remove(path);  // the file just made, not left empty
    throw;
  }
  std::cout << "wrote " << path.string() << " (the soil at rest: open it in ParaView)\n";
  return kExitOk;
}

}  // namespace rumble::cli
