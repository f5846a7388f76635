#include "scenario/document.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <system_error>

#include "core/input_file.hpp"
#include "scenario/json_position.hpp"
#include "scenario/syntax_error.hpp"
#include "scenario/value_text.hpp"

namespace rumble::scenario {
namespace {

namespace fs = std::filesystem;

Diagnostic file_error(std::string message, std::string hint = "") {
  Diagnostic d;
  d.message = std::move(message);
  d.hint = std::move(hint);
  return d;
}

/// "70.0 MiB"; in bytes when that would round to the limit and read like no excess at all.
std::string size_text(std::uintmax_t bytes) {
  if (bytes < kMaxDocumentBytes + (std::uintmax_t{1} << 20))
    return std::to_string(bytes) + " bytes";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
  return buf;
}

Diagnostic too_large(std::uintmax_t bytes) {
  return file_error("file is too large (" + size_text(bytes) + "; the limit is " +
                        std::to_string(kMaxDocumentBytes >> 20) + " MiB)",
                    "a scenario holds parameters, not data; is this the right file?");
}

bool only_whitespace(std::string_view text) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  for (const char c : text) {
    if (c != ' ' && c != '\t' && c != '\n' && c != '\r') return false;
  }
  return true;
}

/// /dev/stdin, /dev/fd/N, /proc/self/fd/N: a descriptor this process was given.
bool names_an_open_descriptor(const fs::path& path) {
  const std::string p = path.lexically_normal().string();
  return p == "/dev/stdin" || p.starts_with("/dev/fd/") || p.starts_with("/proc/self/fd/");
}

}  // namespace

std::optional<Document> load_document(const fs::path& path, std::vector<Diagnostic>& diagnostics) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) {
    if (ec && ec != std::errc::no_such_file_or_directory) {
      diagnostics.push_back(file_error("cannot be read: " + ec.message()));
    } else {
      diagnostics.push_back(
          file_error("file not found", "check the path and the working directory"));
    }
    return std::nullopt;
  }
  if (fs::is_directory(status)) {
    diagnostics.push_back(file_error("is a directory, not a scenario file"));
    return std::nullopt;
  }
  // A pipe or terminal is read only as the process's standard input or a descriptor the shell
  // opened (`rumble validate /dev/stdin < file`, `<(...)`): a FIFO on disk would wait for a
  // writer for ever, a device such as /dev/zero never ends (docs/scenario.md, "Limits").
  if (!fs::is_regular_file(status) && !names_an_open_descriptor(path)) {
    diagnostics.push_back(file_error("is " + file_kind(status) + ", not a regular file",
                                     "give the file itself, or pass it on standard input as "
                                     "/dev/stdin"));
    return std::nullopt;
  }
  if (fs::is_regular_file(status)) {
    const std::uintmax_t size = fs::file_size(path, ec);
    if (!ec && size > kMaxDocumentBytes) {
      diagnostics.push_back(too_large(size));
      return std::nullopt;
    }
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    diagnostics.push_back(file_error(std::string("cannot be read: ") + std::strerror(errno)));
    return std::nullopt;
  }
  // Read at most one byte past the limit: a pipe or device has no size to check up front.
  std::string text;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxDocumentBytes) {
      diagnostics.push_back(too_large(text.size()));
      return std::nullopt;
    }
  }
  if (in.bad()) {
    diagnostics.push_back(file_error(std::string("cannot be read: ") + std::strerror(errno)));
    return std::nullopt;
  }
  return parse_document(path, std::move(text), diagnostics);
}

std::optional<Document> parse_document(fs::path path, std::string text,
                                       std::vector<Diagnostic>& diagnostics) {
  if (text.size() > kMaxDocumentBytes) {
    diagnostics.push_back(too_large(text.size()));
    return std::nullopt;
  }
  if (only_whitespace(text)) {
    diagnostics.push_back(file_error("file is empty", "a scenario is one JSON object: { ... }"));
    return std::nullopt;
  }
  if (const auto deep = find_excess_nesting(text, kMaxNestingDepth)) {
    Diagnostic d = file_error("nesting is too deep (more than " + std::to_string(kMaxNestingDepth) +
                                  " levels of arrays and objects)",
                              "a scenario needs only a few levels; is this the right file?");
    const LineColumn lc = line_column(text, *deep);
    d.line = lc.line;
    d.column = lc.column;
    diagnostics.push_back(std::move(d));
    return std::nullopt;
  }
  Document doc;
  doc.path = std::move(path);
  try {
    doc.json = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    diagnostics.push_back(describe_parse_error(text, e.byte, e.what()));
    return std::nullopt;
  } catch (const nlohmann::json::out_of_range& e) {
    diagnostics.push_back(describe_number_overflow(text, e.what()));
    return std::nullopt;
  } catch (const std::exception& e) {
    diagnostics.push_back(file_error(std::string("cannot be parsed: ") + e.what()));
    return std::nullopt;
  }
  // nlohmann keeps the last of a repeated key and drops the first without a word: a value the
  // user wrote would be ignored. Refused, with both places.
  const auto duplicates = find_duplicate_keys(text);
  for (const DuplicateKey& dup : duplicates) {
    const LineColumn first = line_column(text, dup.first.begin);
    const LineColumn second = line_column(text, dup.second.begin);
    Diagnostic d = file_error(
        "duplicate key " +
            truncate_text(
                std::string_view(text).substr(dup.first.begin, dup.first.end - dup.first.begin),
                60) +
            " (first at line " + std::to_string(first.line) + ", column " +
            std::to_string(first.column) +
            "); JSON keeps only the last value and would drop "
            "the other without a word",
        "keep one of the two");
    d.pointer = dup.pointer;
    d.line = second.line;
    d.column = second.column;
    diagnostics.push_back(std::move(d));
  }
  if (!duplicates.empty()) return std::nullopt;
  doc.text = std::move(text);
  return doc;
}

}  // namespace rumble::scenario
