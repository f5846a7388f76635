#include "fuzz_support.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "scenario/report.hpp"

namespace rumble::fuzz {
namespace {

namespace fs = std::filesystem;

/// The scratch directories made so far, removed when the process exits normally (an input that
/// crashes leaves them in $TMPDIR, which run_fuzzer.sh clears before the next run).
class ScratchDirs {
 public:
  ~ScratchDirs() {
    std::error_code ec;
    if (!root_.empty()) fs::remove_all(root_, ec);
  }
  const fs::path& get(const std::string& name) {
    if (root_.empty()) {
      std::string pattern = (fs::temp_directory_path() / "rumble-fuzz-XXXXXX").string();
      if (::mkdtemp(pattern.data()) == nullptr)
        throw std::runtime_error("cannot make a scratch directory " + pattern);
      root_ = pattern;
    }
    auto [it, fresh] = dirs_.try_emplace(name, root_ / name);
    if (fresh) fs::create_directories(it->second);
    return it->second;
  }

 private:
  fs::path root_;
  std::map<std::string, fs::path> dirs_;
};

}  // namespace

fs::path source_dir() {
  return fs::path(RUMBLE_FUZZ_SOURCE_DIR);
}

const fs::path& scratch_dir(const std::string& name) {
  static ScratchDirs dirs;
  return dirs.get(name);
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_file(const fs::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

std::string tree_listing(const fs::path& dir) {
  std::vector<std::string> lines;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    const fs::file_status st = it->symlink_status(ec);
    std::string line = it->path().lexically_relative(dir).string() + " " +
                       std::to_string(static_cast<int>(st.type()));
    if (fs::is_regular_file(st)) {
      line += " " + std::to_string(it->file_size(ec)) + " " +
              std::to_string(it->last_write_time(ec).time_since_epoch().count());
    }
    lines.push_back(std::move(line));
  }
  std::sort(lines.begin(), lines.end());
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  return out;
}

std::string check_diagnostics(std::string_view text,
                              const std::vector<scenario::Diagnostic>& diagnostics) {
  const std::size_t lines =
      static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) + 1;
  for (const scenario::Diagnostic& d : diagnostics) {
    if (d.message.empty()) return "a diagnostic without a message at \"" + d.pointer + "\"";
    if (d.line > lines)
      return "line " + std::to_string(d.line) + " of a text of " + std::to_string(lines) +
             " lines: " + d.message;
    if (d.line == 0 && d.column != 0) return "a column without a line: " + d.message;
  }
  return "";
}

std::string check_reports(const scenario::Document* doc, const fs::path& file,
                          const std::vector<scenario::Diagnostic>& diagnostics) {
  std::ostringstream plain;
  scenario::print_diagnostics(plain, doc, file, diagnostics, scenario::Format::kText);
  std::ostringstream js;
  scenario::print_diagnostics(js, doc, file, diagnostics, scenario::Format::kJson);
  const nlohmann::json report = nlohmann::json::parse(js.str(), nullptr, false);
  if (report.is_discarded() || !report.contains("diagnostics") ||
      report["diagnostics"].size() != diagnostics.size())
    return "the JSON report does not parse back: " + js.str().substr(0, 200);
  return "";
}

}  // namespace rumble::fuzz
