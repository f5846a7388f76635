// SPDX-License-Identifier: MIT
// rumble/plugin/component.hpp (part of rumble/plugin.hpp, which a plugin includes): what every
// component shares: the exceptions that become statuses, the capability bits, the host and the
// Component base with its checkpoints.
#ifndef RUMBLE_PLUGIN_COMPONENT_HPP
#define RUMBLE_PLUGIN_COMPONENT_HPP

#include <rumble/abi.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace rumble {

/// Thrown by plugin code to refuse a step without changing state (maps to RUMBLE_DISCARD).
class Discard : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Thrown by Host::check_stop() when the host asked the instance to stop (maps to RUMBLE_ERROR).
class Stopped : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Capability bits a class adds in `static constexpr std::uint64_t kCapabilities` (see abi.h).
inline constexpr std::uint64_t kCapThreads = RUMBLE_CAP_THREADS;
inline constexpr std::uint64_t kCapOncePerProcess = RUMBLE_CAP_ONCE_PER_PROCESS;
inline constexpr std::uint64_t kCapSaveRestore = RUMBLE_CAP_SAVE_RESTORE;
inline constexpr std::uint64_t kCapLinearMatrices = RUMBLE_CAP_LINEAR_MATRICES;
inline constexpr std::uint64_t kCapMonolithic = RUMBLE_CAP_MONOLITHIC;
inline constexpr std::uint64_t kCapDistributed = RUMBLE_CAP_DISTRIBUTED;
/// ABI 1.7, vehicle or soil: advance never throws Discard (docs/decisions/0017-never-refuses.md).
inline constexpr std::uint64_t kCapNeverRefuses = RUMBLE_CAP_NEVER_REFUSES;

/// The MPI communicator an instance works on (ABI 1.4, docs/decisions/0012-distributed-soil.md):
/// MPI's Fortran handle, to be turned back with MPI_Comm_f2c; the rank of this process in it and
/// its size. No MPI header here: a plugin that uses MPI includes its own <mpi.h>.
struct HostCommunicator {
  std::int64_t fortran_handle = 0;
  int rank = 0;
  int size = 1;
};

/// Host services (logging, directories, thread budget, stop requests). Cheap to copy; valid for
/// the instance's life.
class Host {
 public:
  explicit Host(const rumble_host* host) : host_(host) {}
  void log(rumble_log_level level, const std::string& message) const {
    if (host_ != nullptr && host_->log != nullptr)
      host_->log(host_->host_data, level, message.c_str());
  }
  void debug(const std::string& m) const { log(RUMBLE_LOG_DEBUG, m); }
  void info(const std::string& m) const { log(RUMBLE_LOG_INFO, m); }
  void warn(const std::string& m) const { log(RUMBLE_LOG_WARN, m); }
  std::string scenario_dir() const {
    return host_ != nullptr && host_->scenario_dir != nullptr ? host_->scenario_dir : ".";
  }
  /// The run's results directory; "" outside a run (validate, soil-frf) or on a 1.0 host.
  std::string results_dir() const {
    return RUMBLE_HAS_FIELD(host_, rumble_host, results_dir) && host_->results_dir != nullptr
               ? host_->results_dir
               : "";
  }
  /// Threads this instance may use inside one call (>= 1); it may change between calls (read it
  /// at each: abi.h, rumble_host::threads).
  unsigned threads() const {
    return RUMBLE_HAS_FIELD(host_, rumble_host, threads) && host_->threads > 0 ? host_->threads
                                                                               : 1u;
  }
  /// Reports progress of the current call (fraction in [0, 1], < 0 unknown); true when the host
  /// asks to stop. Call it every 0.1 s of work or so inside a long call.
  bool stop_requested(double fraction = -1.0) const {
    return RUMBLE_HAS_FIELD(host_, rumble_host, progress) && host_->progress != nullptr &&
           host_->progress(host_->host_data, fraction) != 0;
  }
  /// The instance's communicator (the host starts MPI on the first call); nothing when the host
  /// has no MPI (older than ABI 1.4, or built without it). Throws std::runtime_error when the
  /// host could not start MPI (it logged why).
  std::optional<HostCommunicator> communicator() const {
    if (!RUMBLE_HAS_FIELD(host_, rumble_host, communicator) || host_->communicator == nullptr)
      return std::nullopt;
    HostCommunicator c;
    std::int32_t rank = 0, size = 0;
    if (host_->communicator(host_->host_data, &c.fortran_handle, &rank, &size) != RUMBLE_OK)
      throw std::runtime_error("the host could not give an MPI communicator (see its log)");
    c.rank = rank;
    c.size = size;
    return c;
  }
  /// The MPI ranks the host's command plans for without running on them (`rumble mesh --ranks N`:
  /// N; ABI 1.6): report what each of them would hold. 0: no plan, or a host older than 1.6.
  int planned_ranks() const {
    return RUMBLE_HAS_FIELD(host_, rumble_host, planned_ranks) ? host_->planned_ranks : 0;
  }
  /// stop_requested(), throwing rumble::Stopped when asked to stop.
  void check_stop(double fraction = -1.0) const {
    if (stop_requested(fraction)) throw Stopped("stopped at the host's request (Ctrl-C)");
  }

 private:
  const rumble_host* host_;
};

/// What every component may offer. Checkpoints: the full state in slot 0 ..
/// RUMBLE_CHECKPOINT_SLOTS - 1, which an iterating or retrying coupler saves and restores. One
/// interface, checkpoint_save/restore/free, which the component keeps itself (the host never
/// copies a state: declared as RUMBLE_CAP_OWN_CHECKPOINTS, with RUMBLE_CAP_SAVE_RESTORE), made in
/// one of two ways (docs/plugin-guide.md):
///   - a large state (a FEM soil): override the three and keep each slot's state your own way;
///   - a small state: override state_size/save_state/restore_state (a flat vector of doubles),
///     and the default checkpoint_* keep each slot as such a vector here.
class Component {
 public:
  virtual ~Component() = default;
  /// Number of doubles of the full state; 0 (the default): checkpoints are not offered.
  virtual std::size_t state_size() const { return 0; }
  virtual void save_state(double* /*buffer*/) const {}
  virtual void restore_state(const double* /*buffer*/) {}
  /// Keeps the full state in `slot` (again and again: sized once, no allocation after).
  virtual void checkpoint_save(std::uint32_t slot) {
    const std::size_t n = state_size();
    if (n == 0) throw std::logic_error("checkpoints not offered (state_size() is 0)");
    std::vector<double>& kept = slots_.at(slot);
    kept.resize(n);
    save_state(kept.data());
    saved_.at(slot) = true;
  }
  /// Returns to the state kept in `slot`, which stays kept.
  virtual void checkpoint_restore(std::uint32_t slot) {
    if (!saved_.at(slot))
      throw std::logic_error("checkpoint slot " + std::to_string(slot) + " is empty");
    restore_state(slots_[slot].data());
  }
  /// Releases the memory of `slot`.
  virtual void checkpoint_free(std::uint32_t slot) {
    std::vector<double>().swap(slots_.at(slot));
    saved_.at(slot) = false;
  }
  /// Called once after the last step of a run (flush files, report), before destruction.
  virtual void finalize() {}

  /// Call from any method to make it return RUMBLE_WARNING with this text (result still valid).
  void warn_caller(std::string message) { pending_warning_ = std::move(message); }
  /// Used by the boundary wrappers only.
  std::string take_warning() { return std::exchange(pending_warning_, std::string()); }

 private:
  std::string pending_warning_;
  std::array<std::vector<double>, RUMBLE_CHECKPOINT_SLOTS> slots_;  // default checkpoints only
  std::array<bool, RUMBLE_CHECKPOINT_SLOTS> saved_{};
};

}  // namespace rumble

#endif  // RUMBLE_PLUGIN_COMPONENT_HPP
