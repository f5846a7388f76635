// Owning wrappers around plugin instances. Each keeps its library alive (shared_ptr), gives the
// plugin a host (logging to its own spdlog logger), and turns every status into engine behaviour:
// OK passes, WARNING is logged, DISCARD and ERROR/FATAL throw with the plugin's message. They call
// the plugin's table in the current ABI's shape only, whatever minor it was built for: the
// translation is abi_adapter.hpp's (docs/decisions/0011-abi-wall.md).
#pragma once

#include <rumble/abi.h>

#include <Eigen/SparseCore>
#include <complex>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "core/errors.hpp"
#include "plugin/abi_adapter.hpp"
#include "plugin/mirror_message.hpp"
#include "plugin/registry.hpp"

namespace spdlog {
class logger;
}
namespace rumble::parallel {
class Communicator;
}

namespace rumble {

/// Thrown for RUMBLE_DISCARD: the call was refused and the instance is unchanged.
class Discarded : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Thrown when a plugin refuses its params at creation: a ConfigError whose text gives the
/// component's place, type and library around the plugin's words; plugin_message() is those
/// words alone, for a caller that shows or compares them by themselves (a plugin's own message
/// tests).
class ParamsRefused : public ConfigError {
 public:
  ParamsRefused(const std::string& what, std::string plugin_message)
      : ConfigError(what), plugin_message_(std::move(plugin_message)) {}
  const std::string& plugin_message() const { return plugin_message_; }

 private:
  std::string plugin_message_;
};

struct PluginHandle;

/// The MPI ranks this process's command plans for without running on them (`rumble mesh --ranks
/// N`), given to every instance made after it as rumble_host.planned_ranks (ABI 1.6,
/// docs/decisions/0016-planned-ranks.md); 0: no plan (the default). A process-wide setting, as
/// the ranks of an MPI launch are: one command runs per process.
void set_planned_ranks(int ranks);

class Instance {
 public:
  /// label: where the component sits in the scenario, e.g. "/soil" or "/vehicles/1".
  /// Throws ParamsRefused when the plugin refuses the params.
  Instance(const ComponentType& type, std::string label, const nlohmann::json& params,
           const std::filesystem::path& scenario_dir);
  virtual ~Instance();
  Instance(const Instance&) = delete;
  Instance& operator=(const Instance&) = delete;

  const std::string& type_name() const { return type_.type_name; }
  const std::string& label() const { return label_; }
  const ComponentType& type() const { return type_; }

  const Capabilities& capabilities() const { return type_.capabilities; }
  /// Whether its advance may refuse a step (RUMBLE_DISCARD): it does not promise otherwise
  /// (RUMBLE_CAP_NEVER_REFUSES, ABI 1.7). A refusal despite the promise is a RunError.
  bool may_refuse() const { return !capabilities().has(RUMBLE_CAP_NEVER_REFUSES); }

  /// Checkpoint slots 0 .. RUMBLE_CHECKPOINT_SLOTS - 1, one path whether the plugin keeps them
  /// (own checkpoints) or the engine copies its state (abi::Checkpoints). RunError for a slot
  /// that does not exist, a restore of a slot never saved, or a plugin that cannot save.
  bool can_checkpoint() const;
  /// True when the plugin keeps its checkpoints itself (no state copied across the boundary).
  bool keeps_checkpoints() const { return checkpoints_.plugin_held(); }
  void checkpoint_save(std::uint32_t slot);
  void checkpoint_restore(std::uint32_t slot);
  void checkpoint_free(std::uint32_t slot);

  /// What a run gives the plugin through rumble_host (ABI 1.1): its results directory and the
  /// threads it may use. Set before the run's first call.
  void set_run_context(const std::filesystem::path& results_dir, unsigned threads);
  /// The results directory alone, for a command that writes the instance's files without a run
  /// (`rumble mesh`: the directory of mesh.vtu). Until set, the plugin sees "" and writes none.
  void set_results_dir(const std::filesystem::path& results_dir);
  /// The threads the instance may use (host.threads, at least 1), outside a run: a command that
  /// runs the soil alone (soil-frf, calibrate, mesh, stability) grants it the machine's.
  void grant_threads(unsigned threads);
  /// The lifecycle finalize call (ABI 1.1), when the plugin has one.
  void finalize();

 protected:
  /// Makes one call into the plugin's C table: `fn` returns its status. A status other than OK
  /// or WARNING throws RunError (ERROR/FATAL) or Discarded, naming the call and the plugin; so
  /// does an exception thrown across the C table (a plugin written against abi.h directly may
  /// let one escape), which would otherwise arrive without either.
  template <class Fn>
  rumble_status call(const char* name, Fn&& fn) const {
    rumble_status status = RUMBLE_ERROR;
    try {
      status = fn();
    } catch (const std::exception& e) {
      throw_escaped(name, e.what());
    } catch (...) {
      throw_escaped(name, "an exception not derived from std::exception");
    }
    return check(status, name);
  }
  /// Throws RunError (ERROR/FATAL) or Discarded, naming the call and the plugin.
  rumble_status check(rumble_status status, const char* call) const;
  /// RunError: `call` returned a value that is not finite (`what`: "displacement", at `index`).
  /// When the inputs the engine gave were not finite either (`inputs_finite` false), the
  /// engine's side diverged first and the message says so instead of blaming the plugin.
  [[noreturn]] void throw_not_finite(const char* call, const std::string& what, std::size_t index,
                                     double value, bool inputs_finite = true) const;
  /// RunError: an exception escaped `call` through the C table.
  [[noreturn]] void throw_escaped(const char* call, const std::string& what) const;
  /// "soil 'clm' (/soil)".
  std::string who() const;
  /// The plugin's last_message, "no message" when it gives none (NULL or empty).
  std::string last_message() const;
  rumble_instance* handle() const { return handle_; }

  /// Under an MPI launch, a distributed soil's call is first sent to the other ranks, whose
  /// servers make the same call (plugin/soil_server.hpp), then `body` makes it here, then every
  /// rank's error comes back: this rank's is thrown as it was, another's as a RunError naming
  /// the rank (docs/decisions/0012-distributed-soil.md). Otherwise, and inside such a call (a
  /// call made by another), body() alone. `encode` writes the call's inputs after its id.
  template <class Encode, class Body>
  auto mirrored(mirror::Call call, Encode&& encode, Body&& body) const -> decltype(body()) {
    if (mirror_id_ == 0 || in_mirrored_call_) return body();
    mirror::Writer w;
    w.put(mirror::Service::kSoil).put(call).put(mirror_id_);
    encode(w);
    if constexpr (std::is_void_v<decltype(body())>) {
      run_mirrored(w, [&] { body(); });
    } else {
      std::optional<decltype(body())> result;
      run_mirrored(w, [&] { result.emplace(body()); });
      return std::move(*result);
    }
  }
  /// What every server's copy of this instance is known by; 0 when the instance is not mirrored.
  std::uint64_t mirror_id() const { return mirror_id_; }

 private:
  /// Sends `w`, runs `body`, gathers the ranks' errors and throws the first (see mirrored()).
  void run_mirrored(const mirror::Writer& w, const std::function<void()>& body) const;
  /// The constructor's part under a launch: a distributed soil is created on every rank.
  void create_everywhere(const nlohmann::json& params);
  void create_here(const std::string& params_text);
  /// Under an MPI launch, says once that a soil that is not distributed leaves the other ranks
  /// idle.
  void warn_idle_ranks() const;
  /// The destructor's part: destroys the servers' copies (their errors are logged).
  void destroy_everywhere() noexcept;
  /// Gives the servers' copies this instance's results directory and threads.
  void mirror_host_context() const;
  // The plugin tests (tests/soils/soil_harness) call the plugin's own C table on the handle, to
  // test its statuses and messages past the engine's wrapper; nothing in the engine does.
  friend struct PluginHandle;
  static void log_callback(void* host_data, int32_t level, const char* message);
  static int32_t progress_callback(void* host_data, double fraction);
  /// rumble_host.communicator (ABI 1.4): made on the first call, a duplicate of MPI_COMM_WORLD
  /// for a distributed soil, of MPI_COMM_SELF for anything else; freed with the instance.
  static rumble_status communicator_callback(void* host_data, int64_t* fortran_handle,
                                             int32_t* rank, int32_t* size);
  ComponentType type_;  // a copy: the instance may outlive the registry; type_.library keeps
                        // the code (and the factory and tables it points to) mapped
  std::string label_;
  std::string scenario_dir_;
  std::string results_dir_;
  std::shared_ptr<spdlog::logger> logger_;
  rumble_host host_{};
  const rumble_common_api* common_ = nullptr;
  const rumble_lifecycle_api* lifecycle_ = nullptr;  // null: a 1.0 plugin, or none offered
  abi::Checkpoints checkpoints_;
  std::unique_ptr<parallel::Communicator> communicator_;  // after the handle's destruction
  rumble_instance* handle_ = nullptr;
  std::uint64_t mirror_id_ = 0;            // 0: not mirrored
  mutable bool in_mirrored_call_ = false;  // a mirrored call is running: nested ones are not
};

class VehicleInstance final : public Instance {
 public:
  VehicleInstance(const ComponentType& type, std::string label, const nlohmann::json& params,
                  const std::filesystem::path& scenario_dir);
  std::size_t dof_count() const { return n_dof_; }
  const std::vector<rumble_wheel>& wheels() const { return wheels_; }
  void mass_matrix(const double* q, double* mass) const;
  void forces(double t, const double* q, const double* qd, double* f) const;
  void wheel_kinematics(const double* q, double* z, double* jacobian) const;
  /// False when the plugin offers no analytical tangent.
  bool tangent(double t, const double* q, const double* qd, double* k, double* c) const;
  std::vector<std::string> output_names() const;
  void outputs(double t, const double* q, const double* qd, double* values) const;

 private:
  abi::VehicleCalls calls_;
  std::size_t n_outputs_ = 0;
  std::size_t n_dof_ = 0;
  std::vector<rumble_wheel> wheels_;
};

class SoilInstance final : public Instance {
 public:
  SoilInstance(const ComponentType& type, std::string label, const nlohmann::json& params,
               const std::filesystem::path& scenario_dir);
  void accept_layout(const std::vector<rumble_footprint>& footprints);
  void initialize(double t0, const std::vector<double>& static_force, std::vector<double>& u);
  void advance(double t, double H, const rumble_waveform& force);
  void motion(double* u, double* v, std::size_t n) const;
  /// False when the soil offers no frequency response. receptance: n x n, column-major.
  bool frequency_response(double f_hz, std::size_t n,
                          std::vector<std::complex<double>>& receptance);
  bool set_receivers(const std::vector<rumble_receiver>& receivers);
  void receiver_velocity(double* v, std::size_t n) const;
  /// ABI 1.1 receivers; false when the soil does not declare RUMBLE_CAP_RECEIVERS.
  bool set_probes(const std::vector<rumble_probe>& probes, double sample_interval);
  /// Appends the samples recorded since the last call: times, and per sample
  /// probe_count x RUMBLE_PROBE_VALUES values.
  void take_probe_samples(std::vector<double>& times, std::vector<double>& values);
  std::size_t probe_count() const { return n_probes_; }
  /// ABI 1.3, after set_probes: the highest frequency [Hz] the soil carries to each probe (0:
  /// it cannot say) and how it is found; nothing when the soil does not say. RunError for a
  /// frequency that is negative or not finite.
  struct ProbeResolution {
    std::vector<double> f_hz;
    std::string rule;
  };
  std::optional<ProbeResolution> probe_resolution() const;
  /// ABI 1.5, after accept_layout: the soil's degrees of freedom and its estimate of a run's
  /// peak resident memory [bytes] (0: it cannot say); nothing when the soil does not say.
  /// RunError for an estimate that is negative or not finite.
  struct Size {
    std::uint64_t dofs = 0;
    double peak_bytes = 0.0;
  };
  std::optional<Size> size() const;
  /// ABI 1.5: the static iteration is over (the soil may free what only its statics needed).
  void statics_done();
  /// ABI 1.1 field output: whether write_fields writes anything.
  bool offers_fields() const;
  /// ABI 1.1 field output; false when not offered.
  bool write_fields(double t, const std::filesystem::path& path);
  /// How many pieces a field snapshot has: the ranks of an MPI launch for a distributed soil
  /// (its snapshot is a parallel .pvtu, one .vtu piece per rank: rumble/abi.h, write_fields),
  /// else 1 (one .vtu).
  int field_pieces() const;
  /// ABI 1.1: slowest shear and Rayleigh speeds [m/s]; false when not offered.
  bool wave_speeds(double& c_s_min, double& c_r_min) const;
  /// ABI 1.1, after accept_layout: one matrix of M x'' + C x' + K x = B F (u = B^T x); false
  /// when the soil does not offer RUMBLE_CAP_LINEAR_MATRICES. The CSC the plugin gives is
  /// checked (sizes, sorted in-range indices, finite values): RunError naming the defect.
  bool linear_matrix(rumble_matrix which, Eigen::SparseMatrix<double>& out);

 private:
  void take_probe_samples_here(std::vector<double>& times, std::vector<double>& values);
  bool linear_matrix_here(rumble_matrix which, Eigen::SparseMatrix<double>& out);
  rumble_soil_api api_;          // in the current shape
  std::vector<double> re_, im_;  // scratch for frequency_response
  std::size_t n_probes_ = 0;
};

class CouplerInstance final : public Instance {
 public:
  CouplerInstance(const ComponentType& type, std::string label, const nlohmann::json& params,
                  const std::filesystem::path& scenario_dir);
  /// Returns the coupler's status (ERROR when the host stopped it); never throws for ERROR so
  /// that the caller can tell a host stop from a coupler failure.
  rumble_status run(const rumble_cosim_host& host, double t0, double t_end, double H,
                    std::string& message);

 private:
  rumble_coupler_api api_;  // in the current shape
};

}  // namespace rumble
