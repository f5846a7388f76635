#include "scenario/report.hpp"

#include <cstdio>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "scenario/document.hpp"
#include "scenario/json_position.hpp"

namespace rumble::scenario {
namespace {

/// Makes text safe for a terminal line: control characters and bytes that are not UTF-8 are
/// written as escapes, so that a garbled scenario cannot garble the report.
std::string printable(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    const auto b = static_cast<unsigned char>(s[i]);
    char buf[16];
    if (b < 0x20 || b == 0x7F) {
      std::snprintf(buf, sizeof buf, "\\x%02X", static_cast<unsigned>(b));
      out += buf;
      ++i;
      continue;
    }
    std::size_t len = b < 0x80           ? 1
                      : (b >> 5) == 0x6  ? 2
                      : (b >> 4) == 0xE  ? 3
                      : (b >> 3) == 0x1E ? 4
                                         : 0;
    bool valid = len > 0 && i + len <= s.size();
    for (std::size_t k = 1; valid && k < len; ++k) {
      valid = (static_cast<unsigned char>(s[i + k]) & 0xC0) == 0x80;
    }
    if (!valid) {
      std::snprintf(buf, sizeof buf, "\\x%02X", static_cast<unsigned>(b));
      out += buf;
      ++i;
      continue;
    }
    out.append(s.substr(i, len));
    i += len;
  }
  return out;
}

Diagnostic positioned(const Document* doc, const Diagnostic& d) {
  Diagnostic p = d;
  if (doc != nullptr && p.line == 0 && !p.pointer.empty()) {
    if (const auto span = find_nearest(doc->text, p.pointer, false)) {
      const LineColumn lc = line_column(doc->text, span->begin);
      p.line = lc.line;
      p.column = lc.column;
    }
  }
  return p;
}

std::string count(std::size_t n, const char* word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

}  // namespace

void print_diagnostics(std::ostream& os, const Document* doc, const std::filesystem::path& file,
                       const std::vector<Diagnostic>& diagnostics, Format format) {
  std::size_t errors = 0;
  std::size_t warnings = 0;
  for (const Diagnostic& d : diagnostics) {
    (d.severity == Diagnostic::Severity::kError ? errors : warnings)++;
  }
  if (format == Format::kJson) {
    // Keys in reading order (severity first), not nlohmann's default alphabetical order.
    using ojson = nlohmann::ordered_json;
    ojson out;
    out["file"] = file.string();
    out["diagnostics"] = ojson::array();
    for (const Diagnostic& raw : diagnostics) {
      const Diagnostic d = positioned(doc, raw);
      ojson j;
      j["severity"] = d.severity == Diagnostic::Severity::kError ? "error" : "warning";
      j["pointer"] = d.pointer;
      j["line"] = d.line == 0 ? ojson() : ojson(d.line);
      j["column"] = d.column == 0 ? ojson() : ojson(d.column);
      j["message"] = d.message;
      j["hint"] = d.hint;
      out["diagnostics"].push_back(std::move(j));
    }
    out["errors"] = errors;
    out["warnings"] = warnings;
    os << out.dump(2, ' ', false, ojson::error_handler_t::replace) << '\n';
    return;
  }
  if (diagnostics.empty()) return;
  const std::string name = printable(file.string());
  for (const Diagnostic& raw : diagnostics) {
    const Diagnostic d = positioned(doc, raw);
    os << name;
    if (d.line > 0) os << ':' << d.line << ':' << d.column;
    os << ": " << (d.severity == Diagnostic::Severity::kError ? "error" : "warning") << ": ";
    if (!d.pointer.empty()) os << printable(d.pointer) << ": ";
    os << printable(d.message) << '\n';
    if (!d.hint.empty()) os << "    hint: " << printable(d.hint) << '\n';
  }
  os << count(errors, "error");
  if (warnings > 0) os << ", " << count(warnings, "warning");
  os << '\n';
}

}  // namespace rumble::scenario
