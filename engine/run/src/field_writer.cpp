#include "run/field_writer.hpp"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <rumble/host_resources.hpp>
#include <sstream>

#include "core/errors.hpp"
#include "core/logging.hpp"
#include "core/number_text.hpp"
#include "plugin/instance.hpp"
#include "results/new_file.hpp"
#include "results/results_directory.hpp"

namespace rumble {

namespace fs = std::filesystem;

FieldWriter::FieldWriter(ResultsDirectory& results, SoilInstance& soil, double interval,
                         double t_end, bool size_confirmed)
    : results_(results),
      soil_(soil),
      interval_(interval),
      t_end_(t_end),
      size_confirmed_(size_confirmed) {
  results_.subdirectory("fields");  // a real directory, never a link followed
}

void FieldWriter::at(double t) {
  // Snapshot k is due at k * interval; a step ending within 1e-9 interval of it counts.
  const double due = static_cast<double>(times_.size()) * interval_;
  if (t < due - 1e-9 * interval_) return;
  char stem[48];
  std::snprintf(stem, sizeof stem, "fields/soil_%06zu", times_.size());
  // On N ranks the snapshot is a parallel index and a piece per rank (rumble/abi.h,
  // write_fields); the soil opens each file itself: what stands at a name (a link) is removed.
  const int pieces = soil_.field_pieces();
  const std::string name = std::string(stem) + (pieces > 1 ? ".pvtu" : ".vtu");
  std::vector<fs::path> written = {results_.file(name)};
  for (int r = 0; pieces > 1 && r < pieces; ++r)
    written.push_back(results_.file(std::string(stem) + "_" + std::to_string(r) + ".vtu"));
  for (const fs::path& path : written)
    if (::unlink(path.c_str()) != 0 && errno != ENOENT) {
      const int err = errno;
      throw RunError(write_error(path, err));
    }
  soil_.write_fields(t, written.front());
  times_.push_back(t);
  files_.push_back(name);
  write_index();
  if (times_.size() == 1) check_projected_size(written);
}

void FieldWriter::check_projected_size(const std::vector<fs::path>& first) const {
  double bytes = 0.0;  // (the index and its pieces)
  for (const fs::path& file : first) {
    std::error_code ec;
    bytes += static_cast<double>(fs::file_size(file, ec));
    if (ec) return;
  }
  const double snapshots = std::floor(t_end_ / interval_ + 1e-9) + 1.0;
  // The snapshots still to come must fit the disk, --yes or not.
  const double to_come = bytes * (snapshots - 1.0);
  const std::string dir = first.front().parent_path().string();
  const double free = free_disk_bytes(dir);
  logger("engine")->info(
      "fields: about {} bytes projected ({} snapshots of {} bytes; {} bytes free "
      "there)",
      number_text(bytes * snapshots, 3), number_text(snapshots, 3), number_text(bytes, 3),
      number_text(free, 3));
  std::ostringstream m;
  m.precision(3);
  m << "/outputs/fields/interval: the field snapshots would take about "
    << bytes * snapshots / (1u << 30) << " GiB (" << snapshots << " snapshots of "
    << bytes / (1u << 20) << " MiB, the first one's size), ";
  if (to_come > free) {
    m << "and the " << to_come / (1u << 30) << " GiB still to come are more than the "
      << free / (1u << 30) << " GiB free under " << dir
      << " (--yes does not waive this); raise outputs.fields.interval, shorten the run, or free "
         "space there";
    throw RunError(m.str());
  }
  if (bytes * snapshots <= kMaxFieldBytes || size_confirmed_) return;
  m << "more than the " << kMaxFieldBytes / (1u << 30)
    << " GiB limit; raise outputs.fields.interval, shorten the run, or confirm the size with "
       "--yes";
  throw RunError(m.str());
}

void FieldWriter::write_index() {
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <Collection>\n";
  char time[32];
  for (std::size_t k = 0; k < times_.size(); ++k) {
    std::snprintf(time, sizeof time, "%.9g", times_[k]);
    out << "    <DataSet timestep=\"" << time << "\" group=\"\" part=\"0\" file=\"" << files_[k]
        << "\"/>\n";
  }
  out << "  </Collection>\n</VTKFile>\n";
  replace_file(results_.file("soil.pvd"), results_.file("soil.pvd.tmp"), out.str());
}

}  // namespace rumble
