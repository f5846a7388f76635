// libFuzzer target over scenario text: see scenario_check.hpp for what it checks and
// docs/fuzzing.md for how to build and run it (preset "fuzz", clang-14).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "scenario_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string problem = rumble::fuzz::check_scenario_text(
      std::string_view(reinterpret_cast<const char*>(data), size));
  if (!problem.empty()) {
    std::fprintf(stderr, "scenario fuzz target: %s\n", problem.c_str());
    std::abort();  // libFuzzer saves the input as crash-<sha1> and stops
  }
  return 0;
}
