// Helpers for driving the "loader_test_faulty" fixture soil through its C table, as the engine
// does: create with a host whose log lines are recorded, then call the table directly.
#pragma once

#include <rumble/abi.h>

#include <string>
#include <utility>
#include <vector>

namespace rumble::test {

/// A rumble_host that records every log line as (level, text).
struct RecordingHost {
  RecordingHost() {
    host.struct_size = sizeof(rumble_host);
    host.abi_minor = RUMBLE_ABI_MINOR;
    host.host_data = this;
    host.log = [](void* self, int32_t level, const char* message) {
      static_cast<RecordingHost*>(self)->lines.emplace_back(level, message);
    };
    host.scenario_dir = ".";
  }
  RecordingHost(const RecordingHost&) = delete;
  RecordingHost& operator=(const RecordingHost&) = delete;

  rumble_host host{};
  std::vector<std::pair<int32_t, std::string>> lines;
};

/// n footprints 0.6 m apart along the track.
inline std::vector<rumble_footprint> footprints(std::size_t n) {
  std::vector<rumble_footprint> f(n);
  for (std::size_t i = 0; i < n; ++i) f[i] = {0.6 * static_cast<double>(i), 0.0, 2.6, 0.25};
  return f;
}

/// A held-constant force waveform (order 0) over the given channel values.
struct ConstantForce {
  explicit ConstantForce(std::vector<double> values) : coeff(std::move(values)) {
    waveform = {0, coeff.size(), coeff.data()};
  }
  std::vector<double> coeff;
  rumble_waveform waveform{};
};

}  // namespace rumble::test
