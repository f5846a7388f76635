// A message from rank 0 to the other ranks of a launch as bytes, written on rank 0 and read on
// every other rank (docs/decisions/0012-distributed-soil.md): a call of a distributed soil, or a
// study's runs. Plain values are copied as their bytes: every rank
// runs the same binary on the same kind of machine (an MPI job's ranks do).
#pragma once

#include <rumble/abi.h>

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace rumble::mirror {

/// Whom a message from rank 0 is for on the other ranks: the first byte of every message.
enum class Service : std::uint8_t {
  kSoil = 1,     // a call of a distributed soil (Call below)
  kStudy = 2,    // a study's runs, each rank running its share (study/rank_share.hpp)
  kPhaseEnd = 3  // a run's phase ended: each rank's peak memory (plugin/rank_memory.hpp)
};

/// What a message asks a server to do with its instance (one per mirrored SoilInstance call).
enum class Call : std::uint8_t {
  kCreate,
  kDestroy,
  kHostContext,
  kFinalize,
  kCanCheckpoint,
  kCheckpointSave,
  kCheckpointRestore,
  kCheckpointFree,
  kAcceptLayout,
  kInitialize,
  kAdvance,
  kMotion,
  kFrequencyResponse,
  kSetReceivers,
  kReceiverVelocity,
  kSetProbes,
  kTakeProbeSamples,
  kProbeResolution,
  kWriteFields,
  kLinearMatrix,
  kWaveSpeeds,
  kSize,
  kStaticsDone
};

class Writer {
 public:
  template <class T>
  Writer& put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const char*>(&value);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
    return *this;
  }
  template <class T>
  Writer& put_array(const T* values, std::size_t n) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(static_cast<std::uint64_t>(n));
    const auto* p = reinterpret_cast<const char*>(values);
    bytes_.insert(bytes_.end(), p, p + n * sizeof(T));
    return *this;
  }
  Writer& put_text(const std::string& text) { return put_array(text.data(), text.size()); }
  const std::vector<char>& bytes() const { return bytes_; }

 private:
  std::vector<char> bytes_;
};

class Reader {
 public:
  explicit Reader(const std::vector<char>& bytes) : bytes_(bytes) {}
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value;
    std::memcpy(&value, take(sizeof(T)), sizeof(T));
    return value;
  }
  template <class T>
  std::vector<T> get_array() {
    const auto n = static_cast<std::size_t>(get<std::uint64_t>());
    std::vector<T> values(n);
    if (n > 0) std::memcpy(values.data(), take(n * sizeof(T)), n * sizeof(T));
    return values;
  }
  std::string get_text() {
    const std::vector<char> chars = get_array<char>();
    return std::string(chars.begin(), chars.end());
  }

 private:
  const char* take(std::size_t n) {
    if (at_ + n > bytes_.size()) throw std::logic_error("mirror message shorter than its call");
    const char* p = bytes_.data() + at_;
    at_ += n;
    return p;
  }
  const std::vector<char>& bytes_;
  std::size_t at_ = 0;
};

}  // namespace rumble::mirror
