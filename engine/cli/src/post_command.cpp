// `rumble post RESULTS_DIR [options]`: the vibration indicators of a finished run recomputed from
// its recorded receiver velocities, without rerunning (post/post_run.hpp, docs/post-processing.md):
// PPV per receiver and versus distance, spectra, one-third-octave levels, KB_F,max, guide values
// and wavelet scalograms, into RESULTS_DIR/post/, with the run's scenario's outputs.post under
// the command's options. `rumble run` does the same after every run whose soil recorded receivers.
// The directory is locked meanwhile and the new files are added to its manifest, so a rerun of the
// scenario removes them with the rest.
#include <iostream>

#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "core/errors.hpp"
#include "core/logging.hpp"
#include "post/post_run.hpp"
#include "results/results_directory.hpp"

namespace rumble::cli {
namespace {

constexpr const char* kPostUsage =
    "usage: rumble post RESULTS_DIR [--cwt NAME,NAME...] [--cwt-distances M,M...] "
    "[--f-max HZ] [--reference iso|vdb]";

/// The command line's options over `o` (the run's own).
post::PostOptions options_from(const Arguments& a, post::PostOptions o) {
  if (const auto names = a.value("cwt")) o.cwt_receivers = split_list(*names);
  if (const auto distances = a.value("cwt-distances")) {
    o.cwt_distances.clear();
    for (const std::string& d : split_list(*distances)) {
      try {
        std::size_t used = 0;
        o.cwt_distances.push_back(std::stod(d, &used));
        if (used != d.size()) throw std::invalid_argument(d);
      } catch (const std::exception&) {
        throw UsageError("--cwt-distances " + *distances + ": '" + d +
                         "' is not a distance in metres; e.g. --cwt-distances 2.5,5");
      }
    }
  }
  o.cwt_f_max = a.number("f-max", o.cwt_f_max);
  if (!(o.cwt_f_max > 0.0)) throw UsageError("--f-max must be a frequency above 0 Hz");
  if (a.value("reference")) {
    o.velocity_reference = a.choice("reference", {"iso", "vdb"}, "iso") == "vdb"
                               ? post::kVelocityRefVdb
                               : post::kVelocityRefIso1683;
  }
  return o;
}

}  // namespace

void post_process_run(const std::filesystem::path& results_dir, const post::PostOptions& options) {
  const post::PostResult r = post::post_process(results_dir, options);
  const auto log = logger("post");
  for (const std::string& w : r.warnings) log->warn("{}", w);
  log->info("vibration indicators in {} ({} files)", r.directory.lexically_normal().string(),
            r.files.size());
}

int post_command(const std::vector<std::string>& args) {
  const Arguments a(args, {}, {"cwt", "cwt-distances", "f-max", "reference"});
  if (a.positional().size() != 1) throw UsageError(kPostUsage);
  const post::PostOptions options =
      options_from(a, post::options_from_summary(a.positional().front()));
  ResultsDirectory results(a.positional().front(), ResultsDirectory::Reopen{});
  try {
    post_process_run(results.path(), options);
  } catch (const RunError&) {
    throw;
  } catch (const std::runtime_error& e) {  // what the recorded results lack: the user's to fix
    throw ConfigError(e.what());
  }
  return kExitOk;
}

}  // namespace rumble::cli
