// The libFuzzer entry of every fuzz target here (docs/fuzzing.md: build with the preset "fuzz",
// clang-14). CMakeLists.txt compiles it once per target with RUMBLE_FUZZ_CHECK, the check that
// target runs on each input (<name>_check.hpp says what it checks), and RUMBLE_FUZZ_TARGET, its
// name for the report; the replay test of the other presets runs the same checks.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

namespace rumble::fuzz {
/// "" when every property holds for the input, else what broke.
std::string RUMBLE_FUZZ_CHECK(std::string_view input);
}  // namespace rumble::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string problem =
      rumble::fuzz::RUMBLE_FUZZ_CHECK(std::string_view(reinterpret_cast<const char*>(data), size));
  if (!problem.empty()) {
    std::fprintf(stderr, "%s fuzz target: %s\n", RUMBLE_FUZZ_TARGET, problem.c_str());
    std::abort();  // libFuzzer saves the input as crash-<sha1> and stops
  }
  return 0;
}
