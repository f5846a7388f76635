#include "post_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "fuzz_support.hpp"
#include "post/post_run.hpp"
#include "post/time_series.hpp"

namespace rumble::fuzz {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxPostRows = 1000;
constexpr std::size_t kMaxPostColumns = 24;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// A field as RFC 4180 writes it, always quoted.
std::string quoted_field(const std::string& field) {
  std::string out = "\"";
  for (const char c : field) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string check_table(const post::CsvTable& t, std::string_view csv) {
  if (t.columns.size() != t.names.size())
    return std::to_string(t.columns.size()) + " columns of " + std::to_string(t.names.size()) +
           " names";
  for (std::size_t c = 0; c < t.columns.size(); ++c)
    if (t.columns[c].size() != t.time.size())
      return "column " + std::to_string(c) + " has " + std::to_string(t.columns[c].size()) +
             " rows, the time " + std::to_string(t.time.size());
  const auto lines = static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')) + 1;
  if (t.time.size() + 1 > lines)
    return std::to_string(t.time.size()) + " rows from " + std::to_string(lines) + " lines";
  if (t.warnings.size() > 1) return std::to_string(t.warnings.size()) + " warnings";
  for (const std::string& w : t.warnings)
    if (!contains(w, "receivers.csv")) return "a warning that names no file: " + w;
  return "";
}

/// split_csv_line gives the fields back from their quoted forms (a field without newline: the
/// lines were split at them).
std::string check_split(const std::string& header_line) {
  const std::vector<std::string> fields = post::split_csv_line(header_line);
  std::string joined;
  for (std::size_t i = 0; i < fields.size(); ++i)
    joined += (i ? "," : "") + quoted_field(fields[i]);
  if (post::split_csv_line(joined) != fields)
    return "split_csv_line does not give back the fields of \"" + joined.substr(0, 200) + "\"";
  return "";
}

/// Every line of a CSV file rumble post wrote as wide as its header.
std::string check_written_csv(const fs::path& file) {
  std::istringstream lines(read_file(file));
  std::string line;
  if (!std::getline(lines, line)) return file.filename().string() + " is empty";
  const std::size_t width = post::split_csv_line(line).size();
  for (std::size_t n = 2; std::getline(lines, line); ++n)
    if (post::split_csv_line(line).size() != width)
      return file.filename().string() + ":" + std::to_string(n) + " has not the header's " +
             std::to_string(width) + " fields";
  return "";
}

std::string check_ppv_csv(const fs::path& file, std::size_t receivers) {
  std::istringstream lines(read_file(file));
  std::string line;
  std::getline(lines, line);
  const std::vector<std::string> header = post::split_csv_line(line);
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  const std::size_t distance = column("distance [m]"), ppv = column("PPV_z [m/s]");
  if (distance >= header.size() || ppv >= header.size()) return "ppv.csv without its columns";
  std::size_t rows = 0;
  while (std::getline(lines, line)) {
    const std::vector<std::string> f = post::split_csv_line(line);
    for (const std::size_t c : {distance, ppv}) {
      char* end = nullptr;
      const double v = std::strtod(f.at(c).c_str(), &end);
      if (f[c].empty() || *end != '\0' || !std::isfinite(v))
        return "ppv.csv: '" + header[c] + "' is '" + f[c] + "' in row " + std::to_string(rows + 1);
    }
    ++rows;
  }
  if (rows != receivers)
    return "ppv.csv has " + std::to_string(rows) + " rows for " + std::to_string(receivers) +
           " receivers";
  return "";
}

std::string check_post(std::string_view input) {
  const fs::path dir = scratch_dir("post") / "run";
  std::error_code ec;
  fs::remove_all(dir, ec);
  fs::create_directories(dir);
  const std::size_t marker = input.find(kSummaryMarker);
  const std::string_view csv = input.substr(0, marker);
  write_file(dir / "receivers.csv", csv);
  if (marker != std::string_view::npos)
    write_file(dir / "summary.json", input.substr(marker + kSummaryMarker.size()));

  post::CsvTable table;
  try {
    table = post::read_csv(dir / "receivers.csv");
  } catch (const std::runtime_error& e) {
    if (!contains(e.what(), "receivers.csv"))
      return std::string("read_csv refused without naming the file: ") + e.what();
    return "";
  }
  if (std::string bad = check_table(table, csv); !bad.empty()) return bad;
  if (std::string bad = check_split(std::string(csv.substr(0, csv.find('\n')))); !bad.empty())
    return bad;
  if (table.time.size() > kMaxPostRows || table.names.size() > kMaxPostColumns) return "";

  post::PostResult result;
  try {
    result = post::post_process(dir, post::options_from_summary(dir));
  } catch (const std::runtime_error& e) {
    if (!contains(e.what(), dir.string()))
      return std::string("post_process refused without naming the directory: ") + e.what();
    return "";
  }
  for (const fs::path& f : result.files) {
    if (!fs::is_regular_file(f)) return f.string() + " listed but not written";
    if (f.extension() == ".csv") {
      if (std::string bad = check_written_csv(f); !bad.empty()) return bad;
    }
  }
  const nlohmann::json report =
      nlohmann::json::parse(read_file(result.directory / "post.json"), nullptr, false);
  if (report.is_discarded() || !report.contains("receivers") || !report["receivers"].is_array())
    return "post.json does not parse back";
  if (std::string bad = check_ppv_csv(result.directory / "ppv.csv", report["receivers"].size());
      !bad.empty())
    return bad;
  // The grid the indicators were computed on: at least 2 samples of a finite step > 0.
  const nlohmann::json& sampling = report["sampling"];
  if (!sampling["samples"].is_number_unsigned() || sampling["samples"].get<std::size_t>() < 2 ||
      !sampling["dt_s"].is_number() || !(sampling["dt_s"].get<double>() > 0.0) ||
      !std::isfinite(sampling["dt_s"].get<double>()) || report["receivers"].empty())
    return "post.json: sampling " + sampling.dump() + " for " +
           std::to_string(report["receivers"].size()) + " receivers";
  return "";
}

}  // namespace

std::string check_post_input(std::string_view input) {
  try {
    return check_post(input);
  } catch (const std::exception& e) {
    return std::string("exception escaped: ") + e.what();
  }
}

}  // namespace rumble::fuzz
