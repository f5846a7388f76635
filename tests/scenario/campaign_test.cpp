// The bad-scenario campaign of issue #8, kept so that it repeats: every scenario of the corpus
// (valid/ and the golden cases in invalid/, each with its expected messages) is mutated in fixed,
// seeded ways and put through everything `rumble validate` does (read, parse, schema, relations,
// run size, building the components). For every input the check must return within a bound
// (no crash, no hang), and every finding must say what (a message) and where (a line in the text,
// and a JSON pointer unless it is about the whole file). Labelled "fuzz"; unlike the libFuzzer
// target (tests/fuzz, preset fuzz, docs/fuzzing.md) it is deterministic, runs in every build and
// loads the in-tree plugins. The counts are printed at the end (inputs, findings, refusals by
// exception).
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "core/errors.hpp"
#include "plugin/registry.hpp"
#include "scenario/check_file.hpp"
#include "scenario/scenario.hpp"
#include "test_support.hpp"

namespace rumble::scenario {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kMaxSecondsPerInput = 5.0;  // far above the few milliseconds one takes

struct Tally {
  std::size_t inputs = 0, findings = 0, refused_by_exception = 0, valid = 0;
};

std::vector<fs::path> corpus() {
  std::vector<fs::path> files{test::scenario_test_dir() / "valid" / "minimal.json"};
  for (const auto& e : fs::directory_iterator(test::scenario_test_dir() / "invalid"))
    if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

fs::path scratch() {
  const fs::path dir = fs::path(RUMBLE_TEST_BINARY_DIR) / "test_scratch" / "scenario_campaign";
  fs::create_directories(dir);
  return dir;
}

/// Checks `text` as `rumble validate` would and asserts what holds for any input.
void check(const std::string& text, const std::string& label, Tally& tally) {
  const fs::path file = scratch() / "input.json";
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out << text;
  }
  ++tally.inputs;
  PluginRegistry registry = test::golden_registry();
  std::vector<Override> none;
  const auto start = std::chrono::steady_clock::now();
  std::optional<CheckedScenario> checked;
  try {
    checked = check_scenario_file(file, none, registry);
  } catch (const PluginLoadError& e) {  // a /plugins entry that names no library: exit code 2
    ++tally.refused_by_exception;
    EXPECT_NE(std::string(e.what()).find("/plugins/"), std::string::npos) << label << e.what();
  } catch (const ConfigError& e) {
    ++tally.refused_by_exception;
    EXPECT_FALSE(std::string(e.what()).empty()) << label;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, kMaxSecondsPerInput) << label;
  if (!checked) return;
  if (checked->ok()) ++tally.valid;
  for (const Diagnostic& d : checked->diagnostics) {
    ++tally.findings;
    EXPECT_FALSE(d.message.empty()) << label;
    if (d.message.find("more errors not shown") != std::string::npos) continue;
    if (checked->doc) {
      // About a value: placed in the text, at its pointer (or its nearest ancestor's).
      EXPECT_GT(d.line, 0u) << label << ": " << d.pointer << ": " << d.message;
    } else if (d.message.rfind("file is", 0) != 0) {
      EXPECT_GT(d.line, 0u) << label << ": " << d.message;  // a syntax error: where
    }
  }
  // Both report formats work on it; the JSON one parses back.
  std::ostringstream js;
  print_diagnostics(js, checked->doc ? &*checked->doc : nullptr, file, checked->diagnostics,
                    Format::kJson);
  EXPECT_TRUE(json::accept(js.str())) << label;
}

std::string read(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Text-level: bytes changed, a span deleted, a line repeated (a duplicate key, mostly), digits
// shifted (a number 10^k larger), for every corpus file.
TEST(ScenarioCampaign, TextMutationsOfTheCorpus) {
  Tally tally;
  std::mt19937 rng(8);
  for (const fs::path& f : corpus()) {
    const std::string text = read(f);
    std::uniform_int_distribution<std::size_t> where(0, text.size() - 1);
    std::uniform_int_distribution<int> byte(0, 255);
    for (int i = 0; i < 40; ++i) {
      std::string m = text;
      switch (i % 4) {
        case 0:
          m[where(rng)] = static_cast<char>(byte(rng));
          break;
        case 1: {
          const std::size_t a = where(rng);
          m.erase(a, std::min<std::size_t>(1 + where(rng) % 40, m.size() - a));
          break;
        }
        case 2: {
          const std::size_t a = m.rfind('\n', where(rng));
          const std::size_t b = m.find('\n', a == std::string::npos ? 0 : a + 1);
          if (a != std::string::npos && b != std::string::npos) m.insert(b, m.substr(a, b - a));
          break;
        }
        default: {
          const std::size_t a = m.find_first_of("0123456789", where(rng));
          if (a != std::string::npos) m.insert(a + 1, std::string(1 + where(rng) % 20, '9'));
        }
      }
      check(m, f.filename().string() + " text mutation " + std::to_string(i), tally);
    }
  }
  std::cout << "text campaign: " << tally.inputs << " inputs, " << tally.findings << " findings, "
            << tally.refused_by_exception << " refused by exception, " << tally.valid
            << " valid, 0 crashes, 0 hangs\n";
  EXPECT_GT(tally.findings, tally.inputs / 2);
}

// Value-level: every value of the valid scenario replaced by hostile values of issue #8 (huge,
// tiny, negative, not finite as text, device and escaping paths, huge integers).
TEST(ScenarioCampaign, HostileValuesEverywhere) {
  Tally tally;
  const std::string base_text = read(test::scenario_test_dir() / "valid" / "minimal.json");
  const json base = json::parse(base_text);
  const std::vector<std::string> hostile = {"0",
                                            "-1",
                                            "1e-300",
                                            "1e300",
                                            "1e7",
                                            "2.5",
                                            "9223372036854775807",
                                            "-9223372036854775808",
                                            "18446744073709551616",
                                            "1e-12",
                                            "\"/dev/zero\"",
                                            "\"../../../tmp/x\"",
                                            "\"\"",
                                            "null",
                                            "[]",
                                            "{}"};
  std::vector<std::string> pointers;
  const json flat = base.flatten();  // a named value: range-for over a temporary's items dangles
  for (const auto& [path, value] : flat.items()) pointers.push_back(path);
  for (const std::string& p : pointers) {
    for (const std::string& v : hostile) {
      json j = base;
      j[json::json_pointer(p)] = json::parse(v, nullptr, false, true);
      std::string text = j.dump(2);
      if (v.find('e') != std::string::npos || v.size() > 15) {
        // As written, not as nlohmann prints it back: 1e300 -> "1e+300", big integers exact.
        const std::string printed = json::parse(v).dump();
        const std::size_t at = text.find(printed);
        if (at != std::string::npos) text.replace(at, printed.size(), v);
      }
      check(text, p + " = " + v, tally);
    }
  }
  // The plugins list too: a device, a directory, a missing file.
  for (const char* entry : {"/dev/zero", "/", "missing.so"}) {
    json j = base;
    j["plugins"] = {entry};
    check(j.dump(2), std::string("/plugins/0 = ") + entry, tally);
  }
  std::cout << "value campaign: " << tally.inputs << " inputs, " << tally.findings << " findings, "
            << tally.refused_by_exception << " refused by exception, " << tally.valid
            << " valid, 0 crashes, 0 hangs\n";
  EXPECT_GT(tally.findings, 0u);
}

}  // namespace
}  // namespace rumble::scenario
