#include "test_support.hpp"

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

namespace rumble::scenario::test {

namespace fs = std::filesystem;

fs::path source_dir() {
  return RUMBLE_TEST_SOURCE_DIR;
}
fs::path scenario_test_dir() {
  return source_dir() / "tests" / "scenario";
}

const PluginRegistry& golden_registry() {
  static const PluginRegistry registry = [] {
    const std::set<std::string> wanted = {"single_wheel", "winkler", "gauss_seidel", "jacobi"};
    PluginRegistry r;
    std::error_code ec;
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(RUMBLE_TEST_PLUGIN_DIR, ec)) {
      if (entry.path().extension() == ".so") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) {
      try {
        PluginRegistry probe;  // what does this library provide?
        probe.load_library(f);
        bool useful = false;
        for (const ComponentType& t : probe.types()) useful |= wanted.count(t.type_name) > 0;
        if (useful) r.load_library(f);
      } catch (const std::exception&) {
        // A plugin someone is still writing may not load; the cases that need it say so.
      }
    }
    return r;
  }();
  return registry;
}

std::string missing_plugins(const PluginRegistry& registry, const std::vector<Requirement>& needs) {
  std::string missing;
  for (const Requirement& n : needs) {
    if (registry.find(n.kind, n.type) != nullptr) continue;
    missing +=
        std::string(missing.empty() ? "" : ", ") + kind_name(n.kind) + " plugin '" + n.type + "'";
  }
  if (missing.empty()) return "";
  return "needs " + missing + ", not (yet) built in " + RUMBLE_TEST_PLUGIN_DIR;
}

const std::vector<Requirement>& minimal_needs() {
  static const std::vector<Requirement> needs = {{RUMBLE_KIND_VEHICLE, "single_wheel"},
                                                 {RUMBLE_KIND_SOIL, "winkler"},
                                                 {RUMBLE_KIND_COUPLER, "gauss_seidel"}};
  return needs;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace rumble::scenario::test
