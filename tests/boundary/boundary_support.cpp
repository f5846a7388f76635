#include "boundary_support.hpp"

namespace rumble::testing {

std::string fixture_plugin(const std::string& name) {
  return std::string(FIXTURE_DIR) + "/" + name + ".so";
}

nlohmann::json fixture_scenario(const nlohmann::json& soil, const nlohmann::json& coupling) {
  nlohmann::json s = small_scenario();
  s["plugins"] = {fixture_plugin("boundary_fixtures"), fixture_plugin("abi_fixture_1_0"),
                  fixture_plugin("abi_fixture_1_1")};
  s["soil"] = soil;
  s["coupling"] = coupling;
  return s;
}

std::filesystem::path run_in(const std::string& name, const nlohmann::json& scenario,
                             CliResult& result) {
  const auto dir = scratch_directory(name);
  result = run_rumble({"run", write_scenario(dir, scenario).string(), "--no-progress"});
  return dir / "results";
}

bool same_bytes(const std::filesystem::path& a, const std::filesystem::path& b) {
  const std::string text_a = file_text(a);
  return !text_a.empty() && text_a == file_text(b);
}

}  // namespace rumble::testing
