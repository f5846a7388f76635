#include "plugin/capabilities.hpp"

#include <rumble/abi.h>

namespace rumble {
namespace {

struct Name {
  std::uint64_t bit;
  const char* key;
  const char* phrase;  // completes "a soil that can ..." / "cannot ..."
};

constexpr Name kNames[] = {
    {RUMBLE_CAP_SAVE_RESTORE, "save_restore", "save and restore its state"},
    {RUMBLE_CAP_OWN_CHECKPOINTS, "own_checkpoints", "keep its own checkpoints"},
    {RUMBLE_CAP_FREQUENCY_RESPONSE, "frequency_response", "give its frequency response"},
    {RUMBLE_CAP_RECEIVERS, "receivers", "record receivers"},
    {RUMBLE_CAP_FIELD_OUTPUT, "field_output", "write field output"},
    {RUMBLE_CAP_TANGENT, "tangent", "give an analytic tangent"},
    {RUMBLE_CAP_LINEAR_MATRICES, "linear_matrices", "give its linear matrices"},
    {RUMBLE_CAP_THREADS, "threads", "use threads"},
    {RUMBLE_CAP_ONCE_PER_PROCESS, "once_per_process", "run once per process"},
    {RUMBLE_CAP_WAVE_SPEEDS, "wave_speeds", "give its wave speeds"},
    {RUMBLE_CAP_SURFACE_RECEIVERS, "surface_receivers", "record surface receivers (ABI 1.0)"},
    {RUMBLE_CAP_MONOLITHIC, "monolithic", "have the soil integrated with the track"},
    {RUMBLE_CAP_DISTRIBUTED, "distributed", "run on every rank of an MPI launch"},
    {RUMBLE_CAP_NEVER_REFUSES, "never_refuses", "take every step it is given"}};

}  // namespace

std::vector<std::string> capability_keys(std::uint64_t bits) {
  std::vector<std::string> keys;
  for (const Name& n : kNames)
    if ((bits & n.bit) != 0) keys.emplace_back(n.key);
  return keys;
}

std::string capability_text(std::uint64_t bits) {
  std::string text;
  for (const Name& n : kNames)
    if ((bits & n.bit) != 0) text += (text.empty() ? "" : " and ") + std::string(n.phrase);
  return text.empty() ? "do nothing special" : text;
}

}  // namespace rumble
