#include "run/field_writer.hpp"

#include <cstdio>
#include <fstream>

#include "core/errors.hpp"
#include "plugin/instance.hpp"

namespace rumble {

namespace fs = std::filesystem;

FieldWriter::FieldWriter(const fs::path& results_dir, SoilInstance& soil, double interval)
    : dir_(results_dir), soil_(soil), interval_(interval) {
  std::error_code ec;
  fs::create_directories(dir_ / "fields", ec);
  if (ec) {
    throw RunError("cannot create " + (dir_ / "fields").string() + ": " + ec.message() +
                   "; check that /outputs/directory is writable");
  }
}

void FieldWriter::at(double t) {
  // Snapshot k is due at k * interval; a step ending within 1e-9 interval of it counts.
  const double due = static_cast<double>(times_.size()) * interval_;
  if (t < due - 1e-9 * interval_) return;
  char name[48];
  std::snprintf(name, sizeof name, "fields/soil_%06zu.vtu", times_.size());
  soil_.write_fields(t, dir_ / name);
  times_.push_back(t);
  files_.emplace_back(name);
  write_index();
}

void FieldWriter::write_index() const {
  const fs::path tmp = dir_ / "soil.pvd.tmp";
  {
    std::ofstream out(tmp);
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
    if (!out) {
      throw RunError("cannot write " + tmp.string() +
                     "; check free disk space and that outputs.directory is writable");
    }
  }
  fs::rename(tmp, dir_ / "soil.pvd");
}

}  // namespace rumble
