// Writing the measures as post/'s CSV files. Each is built whole in memory and put in place as a
// new file, so that a reader never sees half of one and a link planted at its name is never
// followed; the columns are docs/post-processing.md's.
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/number_text.hpp"
#include "post_run_steps.hpp"
#include "results/new_file.hpp"

namespace rumble::post::detail {
namespace {

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

/// One CSV file, built in memory and written whole as a new file (results/new_file.hpp: a link
/// planted at its name is replaced, never followed; a reader never sees half of it).
class CsvOut {
 public:
  CsvOut(const fs::path& path, const std::vector<std::string>& header) : path_(path) {
    for (std::size_t i = 0; i < header.size(); ++i) text_ += (i ? "," : "") + csv_field(header[i]);
    text_ += '\n';
  }
  CsvOut& operator<<(const std::string& field) {
    text_ += (first_ ? "" : ",") + csv_field(field);
    first_ = false;
    return *this;
  }
  CsvOut& operator<<(double v) { return *this << number_text(v, 9); }
  void end_row() {
    text_ += '\n';
    first_ = true;
  }
  void close() { write_whole(path_, text_); }

 private:
  fs::path path_;
  std::string text_;
  bool first_ = true;
};

std::vector<std::string> ppv_header() {
  std::vector<std::string> header = {"receiver", "x [m]", "distance [m]", "depth [m]",
                                     "PPV_z [m/s]", "t(PPV_z) [s]", "PPV_3c [m/s]",
                                     "PPV_max_component [m/s]", "component", "f_dom [Hz]",
                                     "KB_F,max [m/s]", "v_eff,F,max [m/s]", "v_rms_z [m/s]",
                                     // The resolved band (nan where the soil does not say).
                                     "f_resolved [Hz]", "energy_z above f_resolved [-]",
                                     "PPV_z resolved [m/s]", "PPV_3c resolved [m/s]"};
  for (auto line : kDinLines) {
    header.push_back(name(line) + " [m/s]");
    header.push_back("PPV / " + name(line) + " [-]");
  }
  for (auto line : kBsLines) {
    header.push_back(name(line) + " [m/s]");
    header.push_back("PPV / " + name(line) + " [-]");
  }
  // Within the resolved band: the other indicators of the low-passed record.
  header.push_back("KB_F,max resolved [m/s]");
  header.push_back("f_dom resolved [Hz]");
  for (auto line : kDinLines) header.push_back("PPV / " + name(line) + " resolved [-]");
  for (auto line : kBsLines) header.push_back("PPV / " + name(line) + " resolved [-]");
  return header;
}

std::string file_name_for(const std::string& receiver) {
  std::string out;
  for (char c : receiver) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '.' || c == '-' || c == '_' || c == '=';
    out += keep ? c : '_';
  }
  return "cwt_" + out + ".csv";
}

}  // namespace

void write_whole(const fs::path& path, const std::string& text) {
  replace_file(path, fs::path(path.string() + ".tmp"), text);
}

void make_directory(const fs::path& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) return;
  if ((::unlink(path.c_str()) != 0 && errno != ENOENT) || ::mkdir(path.c_str(), 0777) != 0) {
    const int err = errno;
    throw std::runtime_error("cannot create " + quoted(path) + ": " + std::strerror(err) +
                             "; check that the results directory is writable");
  }
}

void write_ppv_csv(const std::vector<ReceiverResult>& results, PostResult& result) {
  CsvOut out(result.directory / "ppv.csv", ppv_header());
  for (const ReceiverResult& rr : results) {
    const ComponentResult& g = rr.components[rr.governing];
    out << rr.rx->name << rr.rx->x << rr.rx->distance << rr.rx->depth << rr.ppv_z << rr.t_ppv_z
        << rr.ppv_3c << g.peak.value << g.component << g.dominant_f << rr.kb_f_max << rr.v_eff_max
        << rr.vz().v_rms << rr.rx->resolved_f << rr.energy_above_resolved << rr.ppv_z_resolved
        << rr.ppv_3c_resolved;
    for (const GuideCheck& c : rr.din) out << c.guide << c.ratio;
    for (const GuideCheck& c : rr.bs) out << c.guide << c.ratio;
    out << rr.kb_f_max_resolved << rr.dominant_f_resolved;
    for (const GuideCheck& c : rr.din_resolved) out << c.ratio;
    for (const GuideCheck& c : rr.bs_resolved) out << c.ratio;
    out.end_row();
  }
  out.close();
  result.files.push_back(result.directory / "ppv.csv");
}

void write_spectra_csv(const std::vector<ReceiverResult>& results, double f_max,
                       PostResult& result) {
  std::vector<std::string> header = {"f [Hz]"};
  for (const ReceiverResult& rr : results)
    for (const ComponentResult& c : rr.components)
      header.push_back(rr.rx->name + " " + c.component + " [m/s]");
  CsvOut out(result.directory / "spectra.csv", header);
  const Spectrum& first = results.front().components.front().amplitude;
  for (std::size_t k = 0; k < first.values.size(); ++k) {
    if (first.frequency(k) > f_max) break;
    out << first.frequency(k);
    for (const ReceiverResult& rr : results)
      for (const ComponentResult& c : rr.components) out << c.amplitude.values[k];
    out.end_row();
  }
  out.close();
  result.files.push_back(result.directory / "spectra.csv");
}

void write_third_octave_csv(const std::vector<ReceiverResult>& results,
                            const std::vector<ThirdOctaveBand>& bands, double velocity_reference,
                            PostResult& result) {
  const std::string ref_label = "dB re " + number_text(velocity_reference, 9) + " m/s";
  std::vector<std::string> header = {"band [Hz]", "f_m [Hz]", "f_lower [Hz]", "f_upper [Hz]"};
  for (const ReceiverResult& rr : results)
    for (const ComponentResult& c : rr.components)
      header.push_back(rr.rx->name + " " + c.component + " L_v [" + ref_label + "]");
  CsvOut out(result.directory / "third_octave.csv", header);
  for (std::size_t b = 0; b < bands.size(); ++b) {
    out << bands[b].nominal << bands[b].centre << bands[b].lower << bands[b].upper;
    for (const ReceiverResult& rr : results)
      for (const ComponentResult& c : rr.components) out << c.bands[b].level;
    out.end_row();
  }
  out.close();
  result.files.push_back(result.directory / "third_octave.csv");
}

json write_scalograms(const std::vector<ReceiverResult>& results,
                      const std::vector<std::size_t>& cwt_of, const UniformGrid& grid,
                      const CwtOptions& cwt_options, PostResult& result) {
  json cwt_json = json::array();
  if (cwt_of.empty()) return cwt_json;
  MorletCwt cwt(grid.count, grid.dt, cwt_options);
  std::set<std::string> used;
  for (std::size_t i : cwt_of) {
    const ReceiverResult& rr = results[i];
    const Scalogram s = cwt.transform(rr.vz().v);
    std::string file = file_name_for(rr.rx->name);
    for (int k = 2; used.count(file); ++k)
      file = file_name_for(rr.rx->name + "_" + std::to_string(k));
    used.insert(file);
    std::vector<std::string> header = {"t [s]", "f_coi [Hz]"};
    for (double f : s.frequency) header.push_back("|W| " + number_text(f, 9) + " Hz [m/s]");
    CsvOut out(result.directory / file, header);
    for (std::size_t j = 0; j < s.time.size(); ++j) {
      out << s.time[j] << s.coi_frequency[j];
      for (std::size_t f = 0; f < s.frequency.size(); ++f) out << s.at(f, j);
      out.end_row();
    }
    out.close();
    result.files.push_back(result.directory / file);
    double w_max = 0.0;
    for (double w : s.magnitude) w_max = std::max(w_max, w);
    cwt_json.push_back({{"receiver", rr.rx->name},
                        {"component", "vz"},
                        {"file", file},
                        {"max_abs_w_m_s", number_or_null(w_max)}});
  }
  return cwt_json;
}

}  // namespace rumble::post::detail
