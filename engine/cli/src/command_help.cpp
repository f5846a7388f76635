// `rumble help COMMAND`, `rumble COMMAND --help`: each command's arguments and options, what each
// means and its default. Kept beside the parsers by hand; tests/cli checks every command has one.
#include <map>
#include <string>

#include "cli/commands.hpp"

namespace rumble::cli {
namespace {

// Each command's help (rumble help COMMAND, rumble COMMAND --help).
constexpr const char kRunHelp[] = R"(usage: rumble run FILE [options]

Validates the scenario FILE, then runs it. Results go to outputs.directory, inside the
scenario's folder; the directory is locked for the run and a rerun replaces its own results.

options:
  --output DIR              write the results to DIR instead of outputs.directory (default: the
                            scenario's outputs.directory)
  --overwrite               also replace another scenario's results in the directory, keeping
                            files rumble did not write (default: refuse)
  --allow-outside-results   accept an outputs.directory that is absolute or leads out of the
                            scenario's folder, with ".." or a symbolic link (default: refuse;
                            --output DIR also consents)
  --yes                     run even when validation estimates the run beyond the limits on
                            steps, memory or bytes written (default: refuse, with the estimate)
  --no-progress             no progress line (default: shown when stderr is a terminal)
  --no-plots                no PNG/SVG plots (default: outputs.plots)
  --set POINTER=VALUE       replace the value at a JSON pointer first; repeatable, e.g.
                            --set /soil/params/E=1e7
)";

constexpr const char kValidateHelp[] = R"(usage: rumble validate FILE [options]

Checks the scenario FILE without running it and prints every error at once (JSON pointer,
line:column, value, fix): the schema, the plugins' params, the engine's relations, the run's
estimated size, and the components themselves (their constructors run: plugin code).

options:
  --format text|json        how findings are printed (default: text, on stderr; json: one
                            object on stdout, load errors too)
  --no-load                 do not load the libraries in the scenario's "plugins" list nor
                            build the components: schema and relations only (default: load)
  --set POINTER=VALUE       replace the value at a JSON pointer first; repeatable
)";

constexpr const char kStudyHelp[] = R"(usage: rumble study FILE [options]

Runs a study (docs/study.md): the product of scenario variations and/or a list, each run
validated first, then run as child processes; runs whose results are up to date are skipped.

options:
  --jobs N                  runs at once, 1 to 1024 (default: the study file's "jobs", else
                            half the usable CPUs)
  --force                   rerun every run (default: skip those up to date)
  --dry-run                 list the runs and their state, run nothing
  --no-report               no report plots at the end
  --yes                     run even the runs estimated beyond the limits on steps, memory or
                            bytes written (default: such a run is not valid)
  --allow-outside-results   accept an "output" that is absolute or leads out of the study file's
                            folder, with ".." or a symbolic link (default: refuse)
)";

constexpr const char kPluginsHelp[] = R"(usage: rumble plugins [options]

Lists the plugin libraries found (the engine's plugin directory, RUMBLE_PLUGIN_PATH), where each
came from, the types each provides and their capabilities, and the libraries that could not be
loaded (skipped, with the reason).

Other commands load a library only when a scenario uses one of its types: they learn its types
from its manifest, <library>.manifest.json, which the plugin's build writes (rumble_add_plugin()).

options:
  --format text|json        (default: text; json: one array of libraries on stdout)
  --manifest LIB --output FILE
                            write the manifest of the plugin library LIB to FILE (what
                            rumble_add_plugin() runs after each link)
)";

constexpr const char kSchemaHelp[] = R"(usage: rumble schema [TYPE] [options]

Prints the parameters of a plugin type: units, defaults, ranges. Without TYPE: the known types.

options:
  --json                    the type's params schema as JSON (only JSON on stdout)
)";

constexpr const char kMeshHelp[] = R"(usage: rumble mesh FILE [options]

Builds the scenario's soil on its footprints without running: its report in the log, its
mesh in DIR/mesh.vtu (soils with field output, e.g. fem).

options:
  --output DIR              (default: the scenario's outputs.directory)
  --ranks N                 plan a run on N MPI ranks (mpirun -n N rumble run): the FEM soil
                            reports the largest rank's nodes and DOFs, the halo and the memory
                            per rank, estimated before meshing, then from the mesh split into N
                            parts here by the runs' partitioner (docs/fem-soil.md, "Planning
                            the ranks"); it still meshes on this one process
  --allow-outside-results   accept an outputs.directory that is absolute or leads out of the
                            scenario's folder (default: refuse; --output DIR also consents)
  --set POINTER=VALUE       replace the value at a JSON pointer first; repeatable, e.g.
                            --set /soil/params/mesh/f_max=50
)";

constexpr const char kSoilFrfHelp[] = R"(usage: rumble soil-frf FILE [FILE...] [options]

Receptance of each scenario's soil at its footprints, one CSV per soil, plotted together.

options:
  --fmin HZ                 lowest frequency, > 0 (default: 1)
  --fmax HZ                 highest frequency, > fmin (default: 100)
  --points N                frequencies, log-spaced, an integer from 2 to 100000 (default: 100)
  --terms N                 transfer terms beside the driving point, an integer >= 0 (default: 2)
  --output DIR              a directory for the CSVs (default: <outputs.directory>/soil_frf);
                            locked while written; a rerun replaces its own files
  --overwrite               also replace what another set of scenarios wrote there, keeping
                            files rumble did not write (default: refuse)
  --allow-outside-results   accept a first scenario's outputs.directory that is absolute or
                            leads out of its folder (default: refuse; --output DIR also consents)
  --no-plot                 no plot
)";

constexpr const char kCalibrateHelp[] =
    R"(usage: rumble calibrate TARGET_SCENARIO --model TYPE [options]

Fits a reduced soil's parameters to the receptance of the target scenario's soil over a
frequency band; prints the fitted params (ready to paste) and the residual.

options:
  --model TYPE              the soil type to fit (required)
  --params JSON             its starting params (default: the target's own, when the same type)
  --fit a,b,...             the params to fit (default: every positive number in --params)
  --fmin HZ                 (default: 1)
  --fmax HZ                 (default: 100)
  --points N                an integer from 2 to 100000 (default: 40)
  --terms N                 transfer terms, an integer >= 0 (default: 2)
  --output FILE             also write the report (JSON) to FILE
)";

constexpr const char kStabilityHelp[] = R"(usage: rumble stability FILE [options]

Spectral radius of one gauss_seidel and one jacobi macro step, linearized at rest, for the
scenario's track and linear soil (> 1: the run diverges).

options:
  --macro-steps LIST        comma-separated steps [s] (default: 1e-3,5e-4,2e-4,1e-4)
  --extrapolation P         the schemes' input extrapolation order, 0 to 2 (default: the
                            scenario's coupling params, else 0)
  --interpolation Q         gauss_seidel's force interpolation order, 0 or 1 (default: the
                            scenario's, else 0)
  --output FILE.json        also write the table as JSON
)";

constexpr const char kPostHelp[] = R"(usage: rumble post RESULTS_DIR [options]

Recomputes a finished run's vibration indicators (PPV, spectra, KB, third-octave levels, guide
values, wavelets) into RESULTS_DIR/post; the directory is locked meanwhile.

options:
  --cwt NAME,NAME...        receivers with wavelet scalograms (default: by --cwt-distances)
  --cwt-distances M,M...    distances [m] of the receivers with scalograms (default: 2.5,5)
  --f-max HZ                highest scalogram frequency, > 0 (default: 200; lowered to
                            0.4 / time step when above it)
  --reference iso|vdb       band level reference: iso 1e-9 m/s (ISO 1683), vdb 2.54e-8 m/s
                            (default: iso)
)";

constexpr const char kNewPluginHelp[] = R"(usage: rumble new-plugin KIND NAME [DIR]

Starts a plugin project from the SDK's template, with its own test. KIND: soil, vehicle or
coupler; NAME: the type name (lower case, digits, _); DIR: default ./NAME.
)";

constexpr const char kHelpHelp[] = R"(usage: rumble help [COMMAND]

Prints the overview, or one command's arguments and options with their defaults (also
rumble COMMAND --help).
)";

const std::map<std::string, const char*>& help_texts() {
  static const std::map<std::string, const char*> texts{
      {"run", kRunHelp},          {"validate", kValidateHelp},    {"study", kStudyHelp},
      {"plugins", kPluginsHelp},  {"schema", kSchemaHelp},        {"mesh", kMeshHelp},
      {"soil-frf", kSoilFrfHelp}, {"calibrate", kCalibrateHelp},  {"stability", kStabilityHelp},
      {"post", kPostHelp},        {"new-plugin", kNewPluginHelp}, {"help", kHelpHelp},
  };
  return texts;
}

}  // namespace

const char* command_help(const std::string& command) {
  const auto it = help_texts().find(command);
  return it == help_texts().end() ? nullptr : it->second;
}

}  // namespace rumble::cli
