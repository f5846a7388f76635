// SPDX-License-Identifier: MIT
// rumble/plugin.hpp: the C++ layer of the Rumble SDK. A plugin author derives from Vehicle, Soil
// or Coupler, gives the class three static members, and lists the classes in RUMBLE_PLUGIN():
//
//   class MySoil final : public rumble::Soil {
//    public:
//     static constexpr const char* kTypeName = "my_soil";
//     static constexpr const char* kSummary = "one line shown by `rumble plugins`";
//     static const char* params_schema();   // JSON Schema (draft 7) of the params object
//     MySoil(const std::string& params_json, const rumble::Host& host);
//     ... overrides ...
//   };
//   RUMBLE_PLUGIN("my_soil", "0.1.0", MySoil)
//
// Every exception thrown by plugin code is caught at the boundary: rumble::Discard becomes
// RUMBLE_DISCARD (from advance only: step refused, state unchanged, the caller may retry with a
// smaller step), anything else RUMBLE_ERROR, with what() as the message. The host validates
// params against the schema (and fills declared defaults) before the constructor runs.
//
// Capabilities (ABI 1.1) are declared on the factory, derived at compile time: overriding
// state_size() or checkpoint_save() declares checkpoints (RUMBLE_CAP_SAVE_RESTORE and
// RUMBLE_CAP_OWN_CHECKPOINTS, see Component), frequency_response() the receptance, set_probes()
// receivers, write_fields() field output, wave_speeds() and linear_matrix() likewise,
// Vehicle::tangent() an analytic tangent. What overriding cannot say goes in optional static
// members: kCapabilities (e.g. rumble::kCapThreads | rumble::kCapOncePerProcess),
// kMaxMacroStep [s], and for couplers kSoilNeeds and participants_json(). C++17, standard
// library only.
//
// One way to do each thing: the C++ layer fills the current ABI's entries (the calls with array
// lengths, the lifecycle table), and of ABI 1.0's only those abi.h requires to be non-null.
#ifndef RUMBLE_PLUGIN_HPP
#define RUMBLE_PLUGIN_HPP

#include <rumble/abi.h>

#include <algorithm>
#include <array>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
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

/// A wheel of a vehicle, in the vehicle frame.
using Wheel = rumble_wheel;

/// Model-exchange vehicle: see rumble_vehicle_api in abi.h for the equations and signs.
class Vehicle : public Component {
 public:
  static constexpr rumble_kind kKind = RUMBLE_KIND_VEHICLE;
  virtual std::size_t dof_count() const = 0;
  virtual std::vector<Wheel> wheels() const = 0;
  /// mass: dof x dof, column-major.
  virtual void mass_matrix(const double* q, double* mass) = 0;
  /// Generalized forces except contact; gravity acts in +z (downward).
  virtual void forces(double t, const double* q, const double* qd, double* f) = 0;
  /// z: n_wheels positions [m] (down +, 0 at the nominal height); jacobian: n_wheels x dof.
  virtual void wheel_kinematics(const double* q, double* z, double* jacobian) = 0;
  /// Fill K = -df/dq, C = -df/dq' and return true. Overriding it declares an analytic tangent
  /// (ABI 1.1): return it at every state; a class without one does not override it, and the
  /// engine differentiates forces() numerically.
  virtual bool tangent(double /*t*/, const double* /*q*/, const double* /*qd*/,
                       double* /*stiffness*/, double* /*damping*/) {
    return false;
  }
  /// Optional output channels ("name [unit]"), written by outputs().
  virtual std::vector<std::string> output_names() const { return {}; }
  virtual void outputs(double /*t*/, const double* /*q*/, const double* /*qd*/,
                       double* /*values*/) {}
};

using Footprint = rumble_footprint;
using Receiver = rumble_receiver;

/// A receiver point (ABI 1.1): name, position [m], depth below the surface [m] (>= 0).
struct Probe {
  std::string name;
  double x = 0.0, y = 0.0, depth = 0.0;
};

/// Samples of every probe's motion, recorded by a soil inside advance() and taken by the host
/// after it: per sample a time [s] and n_probes x RUMBLE_PROBE_VALUES values (vx, vy, vz [m/s],
/// ux, uy, uz [m], z down +). Capacity is kept between steps: no allocation in steady state.
class ProbeSamples {
 public:
  void reset(std::size_t n_probes) {
    n_probes_ = n_probes;
    times_.clear();
    values_.clear();
  }
  std::size_t probes() const { return n_probes_; }
  std::size_t pending() const { return times_.size(); }
  /// Forgets the samples not yet taken (the boundary calls it on restore: they belong to a step
  /// that is being taken again).
  void drop_pending() {
    times_.clear();
    values_.clear();
  }
  /// values: n_probes x RUMBLE_PROBE_VALUES.
  void push(double t, const double* values) {
    times_.push_back(t);
    values_.insert(values_.end(), values, values + n_probes_ * RUMBLE_PROBE_VALUES);
  }
  /// Moves up to capacity samples out, oldest first; returns how many.
  std::size_t take(double* times, double* values, std::size_t capacity) {
    const std::size_t n = capacity < times_.size() ? capacity : times_.size();
    const std::size_t width = n_probes_ * RUMBLE_PROBE_VALUES;
    for (std::size_t i = 0; i < n; ++i) times[i] = times_[i];
    for (std::size_t i = 0; i < n * width; ++i) values[i] = values_[i];
    times_.erase(times_.begin(), times_.begin() + static_cast<std::ptrdiff_t>(n));
    values_.erase(values_.begin(), values_.begin() + static_cast<std::ptrdiff_t>(n * width));
    return n;
  }

 private:
  std::size_t n_probes_ = 0;
  std::vector<double> times_, values_;
};

/// A compressed-sparse-column matrix (ABI 1.1 rumble_csc), 0-based, rows sorted per column.
struct CscMatrix {
  std::uint64_t rows = 0, cols = 0;
  std::vector<std::int64_t> col_ptr;  // cols + 1
  std::vector<std::int64_t> row_index;
  std::vector<double> values;
};

/// A force waveform over one macro step (see rumble_waveform).
class Waveform {
 public:
  explicit Waveform(const rumble_waveform& w) : w_(w) {}
  std::size_t channels() const { return static_cast<std::size_t>(w_.n); }
  /// Value of channel i at tau = (t - t_step) / H in [0, 1].
  double at(std::size_t i, double tau) const {
    double value = 0.0;
    for (int k = static_cast<int>(w_.order); k >= 0; --k)
      value = value * tau + w_.coeff[static_cast<std::size_t>(k) * w_.n + i];
    return value;
  }

 private:
  rumble_waveform w_;
};

/// Soil participant: see rumble_soil_api in abi.h.
class Soil : public Component {
 public:
  static constexpr rumble_kind kKind = RUMBLE_KIND_SOIL;
  virtual void accept_layout(const std::vector<Footprint>& footprints) = 0;
  virtual void initialize(double t0, const double* static_force, double* static_u) = 0;
  virtual void advance(double t, double H, const Waveform& force) = 0;
  virtual void motion(double* u, double* v) const = 0;
  /// Return false when not offered; else fill receptance [m/N], n x n column-major.
  virtual bool frequency_response(double /*f_hz*/, std::complex<double>* /*receptance*/) {
    return false;
  }
  /// ABI 1.0 surface receivers (vertical velocity only); prefer set_probes. Return false when
  /// not offered.
  virtual bool set_receivers(const std::vector<Receiver>& /*receivers*/) { return false; }
  virtual void receiver_velocity(double* /*v*/) const {}
  /// Receivers (ABI 1.1): record these points' motion into samples() from now on, at every
  /// internal step (sample_interval 0) or every sample_interval [s]. Throw for a point outside.
  virtual void set_probes(const std::vector<Probe>& /*probes*/, double /*sample_interval*/) {
    throw std::logic_error("receivers not offered");
  }
  /// Write the fields at time t [s] to path (.vtu).
  virtual void write_fields(double /*t*/, const std::string& /*path*/) {
    throw std::logic_error("field output not offered");
  }
  /// Slowest shear and Rayleigh wave speeds [m/s] of any layer.
  virtual void wave_speeds(double& /*c_s_min*/, double& /*c_r_min*/) const {
    throw std::logic_error("wave speeds not offered");
  }
  /// One matrix of M x'' + C x' + K x = B F (u = B^T x), after accept_layout().
  virtual void linear_matrix(rumble_matrix /*which*/, CscMatrix& /*out*/) {
    throw std::logic_error("linear matrices not offered");
  }
  /// ABI 1.3, after set_probes(): the highest frequency [Hz] this soil carries from the
  /// footprints to each probe (one per probe; 0 where it cannot say), with how it is found in
  /// `rule`. Empty (the default): the soil does not say.
  virtual std::vector<double> probe_resolution(std::string& /*rule*/) const { return {}; }
  /// Where advance() records probe samples (sized by the boundary at set_probes()).
  ProbeSamples& samples() { return samples_; }

 private:
  ProbeSamples samples_;
};

/// A named group of a participant's interface channels (ABI 1.1 rumble_channel_group).
struct ChannelGroup {
  std::string name;  // e.g. "footprint_force"
  std::string unit;  // e.g. "N"
  std::size_t offset = 0, count = 0;
};

/// The interface residual of one channel group at the end of a macro step.
struct GroupResidual {
  std::string group;
  double absolute = 0.0;  // [group's unit]
  double relative = 0.0;  // absolute / the group's scale
  double scale = 0.0;     // [group's unit] (SDK 1.3; 0: none known, relative is then absolute)
};

/// What a coupler reports when a macro step is final (ABI 1.1 rumble_step_report).
struct StepReport {
  double t = 0.0, H = 0.0;  // [s]
  std::uint32_t iterations = 1;
  bool converged = true;
  std::vector<GroupResidual> residuals;
  std::uint64_t participants = 0;  // bit p: participant p's step is final; 0: every one
};

/// The host's participant interface as seen by a coupler; errors become exceptions.
class CosimHost {
 public:
  /// Thrown when the host asks the coupler to stop (Ctrl-C, plugin error): status preserved.
  class Stop : public std::runtime_error {
   public:
    Stop(rumble_status s, const std::string& what) : std::runtime_error(what), status(s) {}
    rumble_status status;
  };
  static constexpr std::uint32_t kTrack = RUMBLE_PARTICIPANT_TRACK;
  static constexpr std::uint32_t kSoil = RUMBLE_PARTICIPANT_SOIL;
  static constexpr std::uint32_t kSlots = RUMBLE_CHECKPOINT_SLOTS;

  explicit CosimHost(const rumble_cosim_host* h) : h_(h) {}
  std::size_t interface_size() const {
    return static_cast<std::size_t>(h_->interface_size(h_->ctx));
  }
  std::size_t output_size(std::uint32_t p) const {
    return static_cast<std::size_t>(h_->output_size(h_->ctx, p));
  }
  void get_output(std::uint32_t p, std::vector<double>& y) const {
    check(h_->get_output(h_->ctx, p, y.data(), y.size()), "get_output");
  }
  /// coeff: (order + 1) * channels values, see rumble_waveform.
  void set_input(std::uint32_t p, std::uint32_t order, const std::vector<double>& coeff) const {
    const rumble_waveform w{order, coeff.size() / (order + 1u), coeff.data()};
    check(h_->set_input(h_->ctx, p, &w), "set_input");
  }
  /// Returns OK, WARNING or DISCARD (the participant refused the step and is unchanged: retry
  /// smaller); ERROR/FATAL throw Stop.
  rumble_status advance(std::uint32_t p, double t, double H) const {
    return check(h_->advance(h_->ctx, p, t, H), "advance");
  }
  /// Checkpoint slot 0 .. kSlots - 1 of a participant's full state (where it is kept is the
  /// host's and the participant's business; ask can_checkpoint() first).
  void save(std::uint32_t p, std::uint32_t slot) const {
    check(h_->save(h_->ctx, p, slot), "save");
  }
  void restore(std::uint32_t p, std::uint32_t slot) const {
    check(h_->restore(h_->ctx, p, slot), "restore");
  }
  /// A final step with one residual, as ABI 1.0 couplers reported it: step_report() of one group,
  /// "interface", final for every participant. Kept so that their source still builds; new code
  /// calls step_report().
  void step_done(double t, double H, double residual) const {
    StepReport r;
    r.t = t;
    r.H = H;
    r.residuals = {{"interface", residual, residual}};
    step_report(r);
  }
  void log(rumble_log_level level, const std::string& m) const {
    h_->log(h_->ctx, level, m.c_str());
  }

  // ---- ABI 1.1 (the host is at least 1.1: a 1.1 plugin never loads into a 1.0 host)
  std::uint32_t participant_count() const { return h_->participant_count(h_->ctx); }
  std::string participant_name(std::uint32_t p) const {
    const char* name = h_->participant_name(h_->ctx, p);
    return name != nullptr ? name : "";
  }
  /// Index of the participant called name; throws Stop when there is none.
  std::uint32_t participant(const std::string& name) const {
    for (std::uint32_t p = 0; p < participant_count(); ++p)
      if (participant_name(p) == name) return p;
    throw Stop(RUMBLE_ERROR, "no participant named '" + name + "'");
  }
  /// Channel groups of a participant's outputs (RUMBLE_SIDE_OUTPUT) or inputs.
  std::vector<ChannelGroup> groups(std::uint32_t p, std::uint32_t side) const {
    std::uint64_t n = 0;
    check(h_->channel_groups(h_->ctx, p, side, nullptr, 0, &n), "channel_groups");
    std::vector<rumble_channel_group> raw(static_cast<std::size_t>(n));
    check(h_->channel_groups(h_->ctx, p, side, raw.data(), n, &n), "channel_groups");
    std::vector<ChannelGroup> out;
    for (const rumble_channel_group& g : raw)
      out.push_back(
          {g.name, g.unit, static_cast<std::size_t>(g.offset), static_cast<std::size_t>(g.count)});
    return out;
  }
  void step_report(const StepReport& r) const {
    std::vector<rumble_group_residual>& raw = residuals_;  // reused: no allocation per step
    raw.clear();
    for (const GroupResidual& g : r.residuals)
      raw.push_back({g.group.c_str(), g.absolute, g.relative});
    rumble_step_report report{};
    report.struct_size = sizeof(rumble_step_report);
    report.iterations = r.iterations;
    report.t = r.t;
    report.H = r.H;
    report.converged = r.converged ? 1 : 0;
    report.n_residuals = static_cast<std::uint32_t>(raw.size());
    report.residuals = raw.data();
    report.participants = r.participants;
    check(h_->step_report(h_->ctx, &report), "step_report");
  }
  void free_checkpoint(std::uint32_t p, std::uint32_t slot) const {
    check(h_->free_checkpoint(h_->ctx, p, slot), "free_checkpoint");
  }
  bool can_checkpoint(std::uint32_t p) const { return h_->can_checkpoint(h_->ctx, p) != 0; }

  // ---- ABI 1.4
  /// The footprints every soil accepted, in channel order: footprint i is channel i of the
  /// footprint_force [N], footprint_displacement [m] and footprint_velocity [m/s] groups (x, y
  /// of its centre [m]; length across and width along the track [m]). For a coupler that
  /// applies loads of its own (docs/couplers.md, "The coupler contract"). Throws Stop on a host
  /// that does not give it (older than ABI 1.4: such a host refuses a 1.4 coupler anyway).
  std::vector<Footprint> footprints() const {
    if (!RUMBLE_HAS_FIELD(h_, rumble_cosim_host, footprint_layout) ||
        h_->footprint_layout == nullptr)
      throw Stop(RUMBLE_ERROR, "the host gives no footprint layout (ABI 1.4 appended it)");
    std::uint64_t n = 0;
    check(h_->footprint_layout(h_->ctx, nullptr, 0, &n), "footprint_layout");
    std::vector<Footprint> out(static_cast<std::size_t>(n));
    check(h_->footprint_layout(h_->ctx, out.data(), n, &n), "footprint_layout");
    out.resize(static_cast<std::size_t>(n));
    return out;
  }

 private:
  rumble_status check(rumble_status s, const char* what) const {
    if (s == RUMBLE_ERROR || s == RUMBLE_FATAL)
      throw Stop(s, std::string("host ") + what + " stopped the run");
    return s;
  }
  const rumble_cosim_host* h_;
  mutable std::vector<rumble_group_residual> residuals_;
};

/// Coupling scheme: the master algorithm over macro steps.
class Coupler : public Component {
 public:
  static constexpr rumble_kind kKind = RUMBLE_KIND_COUPLER;
  virtual void run(const CosimHost& host, double t0, double t_end, double H) = 0;
};

namespace detail {

struct Box {
  std::unique_ptr<Component> object;
  std::string message;
  std::size_t n_footprints = 0;         // soil: the accepted layout's size
  std::size_t n_dof = 0, n_wheels = 0;  // vehicle: read once at creation (fixed for life)
  std::size_t n_outputs = 0;            // vehicle: output channels
  std::vector<std::string> names;       // vehicle: output names (ABI 1.1 output_names2)
  std::vector<const char*> name_ptrs;   // ... and the pointers handed out
  CscMatrix matrix;                     // soil: linear_matrix between size query and fill
  std::int32_t matrix_which = -1;       // which matrix `matrix` holds
  std::string resolution_rule;          // soil: probe_resolution's rule, held for the host
};

inline Box* box(rumble_instance* self) {
  return reinterpret_cast<Box*>(self);
}
inline const Box* box(const rumble_instance* self) {
  return reinterpret_cast<const Box*>(self);
}

template <class T>
T& object(rumble_instance* self) {
  return static_cast<T&>(*box(self)->object);
}

/// Runs f, mapping every exception to a status with the message kept on the instance.
template <class F>
rumble_status guard(rumble_instance* self, F&& f) noexcept {
  Box* b = box(self);
  try {
    f();
    std::string w = b->object->take_warning();
    if (w.empty()) return RUMBLE_OK;
    b->message = std::move(w);
    return RUMBLE_WARNING;
  } catch (const Discard& e) {
    b->message = e.what();
    return RUMBLE_DISCARD;
  } catch (const CosimHost::Stop& e) {
    b->message = e.what();
    return e.status;
  } catch (const std::exception& e) {
    b->message = e.what();
    return RUMBLE_ERROR;
  } catch (...) {
    b->message = "unknown exception (not derived from std::exception)";
    return RUMBLE_ERROR;
  }
}

/// A restored soil takes its step again: samples recorded since the host last took them are void.
inline void drop_probe_samples(Component& c) {
  if (auto* soil = dynamic_cast<Soil*>(&c)) soil->samples().drop_pending();
}

/// Throws when a caller's array length differs from what the component expects.
inline void check_length(const char* call, const char* what, std::uint64_t given,
                         std::size_t expected) {
  if (given != expected) {
    throw std::invalid_argument(std::string(call) + ": " + what + " has " + std::to_string(given) +
                                " entries, expected " + std::to_string(expected));
  }
}

/// True when T declares (or inherits from a class other than Base) its own F: decltype(&T::f)
/// names the class the member was found in.
#define RUMBLE_DETAIL_OVERRIDES(T, Base, f) (!std::is_same_v<decltype(&T::f), decltype(&Base::f)>)

template <class T, class = void>
struct ExtraCapabilities : std::integral_constant<std::uint64_t, 0> {};
template <class T>
struct ExtraCapabilities<T, std::void_t<decltype(T::kCapabilities)>>
    : std::integral_constant<std::uint64_t, T::kCapabilities> {};

template <class T, class = void>
struct MaxMacroStep {
  static constexpr double value = 0.0;
};
template <class T>
struct MaxMacroStep<T, std::void_t<decltype(T::kMaxMacroStep)>> {
  static constexpr double value = T::kMaxMacroStep;
};

template <class T, class = void>
struct SoilNeeds : std::integral_constant<std::uint64_t, 0> {};
template <class T>
struct SoilNeeds<T, std::void_t<decltype(T::kSoilNeeds)>>
    : std::integral_constant<std::uint64_t, T::kSoilNeeds> {};

template <class T, class = void>
struct ParticipantsJson {
  static const char* get() { return "{}"; }
};
template <class T>
struct ParticipantsJson<T, std::void_t<decltype(T::participants_json())>> {
  static const char* get() { return T::participants_json(); }
};

/// The capabilities T declares: derived from what it overrides, plus its static members.
template <class T>
const rumble_capabilities* capabilities() {
  static const rumble_capabilities caps = [] {
    rumble_capabilities c{};
    c.struct_size = sizeof(rumble_capabilities);
    std::uint64_t offers = ExtraCapabilities<T>::value;
    if (RUMBLE_DETAIL_OVERRIDES(T, Component, state_size) ||
        RUMBLE_DETAIL_OVERRIDES(T, Component, checkpoint_save))  // Component: kept either way
      offers |= RUMBLE_CAP_OWN_CHECKPOINTS | RUMBLE_CAP_SAVE_RESTORE;
    if constexpr (std::is_base_of_v<Vehicle, T>) {
      if (RUMBLE_DETAIL_OVERRIDES(T, Vehicle, tangent)) offers |= RUMBLE_CAP_TANGENT;
    }
    if constexpr (std::is_base_of_v<Soil, T>) {
      if (RUMBLE_DETAIL_OVERRIDES(T, Soil, frequency_response))
        offers |= RUMBLE_CAP_FREQUENCY_RESPONSE;
      if (RUMBLE_DETAIL_OVERRIDES(T, Soil, set_probes)) offers |= RUMBLE_CAP_RECEIVERS;
      if (RUMBLE_DETAIL_OVERRIDES(T, Soil, set_receivers)) offers |= RUMBLE_CAP_SURFACE_RECEIVERS;
      if (RUMBLE_DETAIL_OVERRIDES(T, Soil, write_fields)) offers |= RUMBLE_CAP_FIELD_OUTPUT;
      if (RUMBLE_DETAIL_OVERRIDES(T, Soil, wave_speeds)) offers |= RUMBLE_CAP_WAVE_SPEEDS;
      if (RUMBLE_DETAIL_OVERRIDES(T, Soil, linear_matrix)) offers |= RUMBLE_CAP_LINEAR_MATRICES;
    }
    c.offers = offers;
    c.soil_needs = SoilNeeds<T>::value;
    c.max_macro_step = MaxMacroStep<T>::value;
    c.participants_json = ParticipantsJson<T>::get();
    return c;
  }();
  return &caps;
}

inline const rumble_lifecycle_api* lifecycle_api() {
  static const rumble_lifecycle_api api = [] {
    rumble_lifecycle_api a{};
    a.struct_size = sizeof(rumble_lifecycle_api);
    a.finalize = [](rumble_instance* self) {
      return guard(self, [&] { box(self)->object->finalize(); });
    };
    a.checkpoint_save = [](rumble_instance* self, std::uint32_t slot) {
      return guard(self, [&] { box(self)->object->checkpoint_save(slot); });
    };
    a.checkpoint_restore = [](rumble_instance* self, std::uint32_t slot) {
      return guard(self, [&] {
        box(self)->object->checkpoint_restore(slot);
        drop_probe_samples(*box(self)->object);
      });
    };
    a.checkpoint_free = [](rumble_instance* self, std::uint32_t slot) {
      return guard(self, [&] { box(self)->object->checkpoint_free(slot); });
    };
    return a;
  }();
  return &api;
}

inline rumble_common_api common_api() {
  rumble_common_api c{};
  c.destroy = [](rumble_instance* self) { delete box(self); };
  c.last_message = [](const rumble_instance* self) { return box(self)->message.c_str(); };
  c.state_size = [](rumble_instance* self, std::uint64_t* n) {
    return guard(self, [&] { *n = box(self)->object->state_size(); });
  };
  c.save_state = [](rumble_instance* self, double* buffer, std::uint64_t n) {
    return guard(self, [&] {
      if (n != box(self)->object->state_size())
        throw std::invalid_argument("save_state: wrong buffer size");
      box(self)->object->save_state(buffer);
    });
  };
  c.restore_state = [](rumble_instance* self, const double* buffer, std::uint64_t n) {
    return guard(self, [&] {
      if (n != box(self)->object->state_size())
        throw std::invalid_argument("restore_state: wrong buffer size");
      box(self)->object->restore_state(buffer);
      drop_probe_samples(*box(self)->object);
    });
  };
  return c;
}

/// The vehicle's functions of ABI 1.0 that abi.h requires to be non-null; its optional ones
/// (tangent, output_names, outputs) stay null: a host calls their forms with lengths.
template <class T>
void vehicle_functions_1_0(rumble_vehicle_api& a) {
  a.dof_count = [](rumble_instance* s, std::uint64_t* n) {
    return guard(s, [&] { *n = object<T>(s).dof_count(); });
  };
  a.wheels = [](rumble_instance* s, rumble_wheel* out, std::uint64_t cap, std::uint64_t* n) {
    return guard(s, [&] {
      const std::vector<Wheel> w = object<T>(s).wheels();
      *n = w.size();
      for (std::size_t i = 0; i < w.size() && i < cap; ++i) out[i] = w[i];
    });
  };
  a.mass_matrix = [](rumble_instance* s, const double* q, double* m) {
    return guard(s, [&] { object<T>(s).mass_matrix(q, m); });
  };
  a.forces = [](rumble_instance* s, double t, const double* q, const double* qd, double* f) {
    return guard(s, [&] { object<T>(s).forces(t, q, qd, f); });
  };
  a.wheel_kinematics = [](rumble_instance* s, const double* q, double* z, double* j) {
    return guard(s, [&] { object<T>(s).wheel_kinematics(q, z, j); });
  };
}

/// The vehicle's functions ABI 1.1 appended: the same calls with the length of every array.
template <class T>
void vehicle_functions_1_1(rumble_vehicle_api& a) {
  a.mass_matrix2 = [](rumble_instance* s, const double* q, std::uint64_t n, double* m,
                      std::uint64_t n_m) {
    return guard(s, [&] {
      const std::size_t dof = box(s)->n_dof;
      check_length("mass_matrix", "q", n, dof);
      check_length("mass_matrix", "mass", n_m, dof * dof);
      object<T>(s).mass_matrix(q, m);
    });
  };
  a.forces2 = [](rumble_instance* s, double t, const double* q, const double* qd, std::uint64_t n,
                 double* f) {
    return guard(s, [&] {
      check_length("forces", "q", n, box(s)->n_dof);
      object<T>(s).forces(t, q, qd, f);
    });
  };
  a.wheel_kinematics2 = [](rumble_instance* s, const double* q, std::uint64_t n, double* z,
                           std::uint64_t n_wheels, double* j) {
    return guard(s, [&] {
      check_length("wheel_kinematics", "q", n, box(s)->n_dof);
      check_length("wheel_kinematics", "z", n_wheels, box(s)->n_wheels);
      object<T>(s).wheel_kinematics(q, z, j);
    });
  };
  a.tangent2 = [](rumble_instance* s, double t, const double* q, const double* qd, std::uint64_t n,
                  double* k, double* c) {
    bool known = false;
    const rumble_status st = guard(s, [&] {
      check_length("tangent", "q", n, box(s)->n_dof);
      known = object<T>(s).tangent(t, q, qd, k, c);
      if (!known) {
        throw std::logic_error(
            "tangent() returned false, but overriding it declares an analytic tangent: return "
            "it at every state, or do not override tangent() (the engine then differentiates "
            "forces())");
      }
    });
    return st;
  };
  a.output_names2 = [](rumble_instance* s, const char** names, std::uint64_t cap,
                       std::uint64_t* n) {
    return guard(s, [&] {
      Box* b = box(s);
      b->names = object<T>(s).output_names();
      b->name_ptrs.clear();
      for (const std::string& name : b->names) b->name_ptrs.push_back(name.c_str());
      *n = b->names.size();
      for (std::size_t i = 0; i < b->name_ptrs.size() && i < cap; ++i) names[i] = b->name_ptrs[i];
    });
  };
  a.outputs2 = [](rumble_instance* s, double t, const double* q, const double* qd, std::uint64_t n,
                  double* v, std::uint64_t n_v) {
    return guard(s, [&] {
      check_length("outputs", "q", n, box(s)->n_dof);
      check_length("outputs", "values", n_v, box(s)->n_outputs);
      object<T>(s).outputs(t, q, qd, v);
    });
  };
}

template <class T>
const rumble_vehicle_api* vehicle_api() {
  static const rumble_vehicle_api api = [] {
    rumble_vehicle_api a{};
    a.struct_size = sizeof(rumble_vehicle_api);
    a.common = common_api();
    vehicle_functions_1_0<T>(a);
    a.lifecycle = lifecycle_api();
    vehicle_functions_1_1<T>(a);
    return a;
  }();
  return &api;
}

/// The soil's functions of ABI 1.0 (rumble_soil_api up to lifecycle).
template <class T>
void soil_functions_1_0(rumble_soil_api& a) {
  a.accept_layout = [](rumble_instance* s, const rumble_footprint* fp, std::uint64_t n) {
    return guard(s, [&] {
      object<T>(s).accept_layout(std::vector<Footprint>(fp, fp + n));
      box(s)->n_footprints = static_cast<std::size_t>(n);
    });
  };
  a.initialize = [](rumble_instance* s, double t0, const double* f, double* u, std::uint64_t n) {
    return guard(s, [&] {
      check_length("initialize", "static_force", n, box(s)->n_footprints);
      object<T>(s).initialize(t0, f, u);
    });
  };
  a.advance = [](rumble_instance* s, double t, double H, const rumble_waveform* w) {
    return guard(s, [&] {
      check_length("advance", "force waveform", w->n, box(s)->n_footprints);
      object<T>(s).advance(t, H, Waveform(*w));
    });
  };
  a.motion = [](rumble_instance* s, double* u, double* v, std::uint64_t n) {
    return guard(s, [&] {
      check_length("motion", "u", n, box(s)->n_footprints);
      object<T>(s).motion(u, v);
    });
  };
  a.frequency_response = [](rumble_instance* s, double f, double* re, double* im, std::uint64_t n) {
    return guard(s, [&] {
      std::vector<std::complex<double>> h(static_cast<std::size_t>(n * n));
      if (!object<T>(s).frequency_response(f, h.data()))
        throw std::logic_error("frequency response not offered");
      for (std::size_t k = 0; k < h.size(); ++k) {
        re[k] = h[k].real();
        im[k] = h[k].imag();
      }
    });
  };
  a.set_receivers = [](rumble_instance* s, const rumble_receiver* r, std::uint64_t n) {
    return guard(s, [&] {
      if (!object<T>(s).set_receivers(std::vector<Receiver>(r, r + n)))
        throw std::logic_error("receivers not offered");
    });
  };
  a.receiver_velocity = [](rumble_instance* s, double* v, std::uint64_t) {
    return guard(s, [&] { object<T>(s).receiver_velocity(v); });
  };
}

/// The soil's functions ABI 1.1 and later appended: probes, fields, wave speeds, linear
/// matrices and (1.3) the probes' resolved band.
template <class T>
void soil_functions_1_1(rumble_soil_api& a) {
  a.set_probes = [](rumble_instance* s, const rumble_probe* p, std::uint64_t n, double dt) {
    return guard(s, [&] {
      std::vector<Probe> probes;
      for (std::uint64_t i = 0; i < n; ++i)
        probes.push_back({p[i].name != nullptr ? p[i].name : "", p[i].x, p[i].y, p[i].depth});
      object<T>(s).samples().reset(probes.size());
      object<T>(s).set_probes(probes, dt);
    });
  };
  a.probe_samples = [](rumble_instance* s, double* times, double* values, std::uint64_t cap,
                       std::uint64_t* n) {
    return guard(s, [&] {
      ProbeSamples& samples = object<T>(s).samples();
      *n =
          cap == 0 ? samples.pending() : samples.take(times, values, static_cast<std::size_t>(cap));
    });
  };
  a.write_fields = [](rumble_instance* s, double t, const char* path) {
    return guard(s, [&] { object<T>(s).write_fields(t, path != nullptr ? path : ""); });
  };
  a.wave_speeds = [](rumble_instance* s, double* c_s, double* c_r) {
    return guard(s, [&] { object<T>(s).wave_speeds(*c_s, *c_r); });
  };
  a.linear_matrix = [](rumble_instance* s, std::int32_t which, rumble_csc* out) {
    return guard(s, [&] {
      Box* b = box(s);
      if (out->values == nullptr || b->matrix_which != which) {  // size query (or stale)
        b->matrix = CscMatrix{};
        object<T>(s).linear_matrix(static_cast<rumble_matrix>(which), b->matrix);
        b->matrix_which = which;
      }
      const CscMatrix& m = b->matrix;
      out->rows = m.rows;
      out->cols = m.cols;
      out->nnz = m.values.size();
      if (out->values == nullptr) return;
      std::copy(m.col_ptr.begin(), m.col_ptr.end(), out->col_ptr);
      std::copy(m.row_index.begin(), m.row_index.end(), out->row_index);
      std::copy(m.values.begin(), m.values.end(), out->values);
      b->matrix = CscMatrix{};  // filled: release it
      b->matrix_which = -1;
    });
  };
  a.probe_resolution = [](rumble_instance* s, double* f_hz, std::uint64_t n, const char** rule) {
    return guard(s, [&] {
      Box* b = box(s);
      const std::vector<double> f = object<T>(s).probe_resolution(b->resolution_rule);
      if (!f.empty()) check_length("probe_resolution", "f_hz", n, f.size());
      for (std::uint64_t i = 0; i < n; ++i) f_hz[i] = f.empty() ? 0.0 : f[i];
      if (rule != nullptr) *rule = f.empty() ? nullptr : b->resolution_rule.c_str();
    });
  };
}

template <class T>
const rumble_soil_api* soil_api() {
  static const rumble_soil_api api = [] {
    rumble_soil_api a{};
    a.struct_size = sizeof(rumble_soil_api);
    a.common = common_api();
    soil_functions_1_0<T>(a);
    a.lifecycle = lifecycle_api();
    soil_functions_1_1<T>(a);
    return a;
  }();
  return &api;
}

template <class T>
const rumble_coupler_api* coupler_api() {
  static const rumble_coupler_api api = [] {
    rumble_coupler_api a{};
    a.struct_size = sizeof(rumble_coupler_api);
    a.common = common_api();
    a.run = [](rumble_instance* s, const rumble_cosim_host* h, double t0, double t1, double H) {
      return guard(s, [&] { object<T>(s).run(CosimHost(h), t0, t1, H); });
    };
    a.lifecycle = lifecycle_api();
    return a;
  }();
  return &api;
}

template <class T>
rumble_status create(const char* params, const rumble_host* host, rumble_instance** out,
                     const char** error) noexcept {
  thread_local std::string message;
  try {
    auto b = std::make_unique<Box>();
    auto object = std::make_unique<T>(std::string(params != nullptr ? params : "{}"), Host(host));
    if constexpr (std::is_base_of_v<Vehicle, T>) {  // sizes checked at every call, read once
      b->n_dof = object->dof_count();
      b->n_wheels = object->wheels().size();
      b->n_outputs = object->output_names().size();
    }
    b->object = std::move(object);
    *out = reinterpret_cast<rumble_instance*>(b.release());
    return RUMBLE_OK;
  } catch (const std::exception& e) {
    message = e.what();
  } catch (...) {
    message = "unknown exception (not derived from std::exception)";
  }
  *out = nullptr;
  *error = message.c_str();
  return RUMBLE_ERROR;
}

template <class T>
rumble_factory factory() {
  static_assert(std::is_base_of_v<Component, T>, "derive from rumble::Vehicle, Soil or Coupler");
  rumble_factory f{};
  f.struct_size = sizeof(rumble_factory);
  f.kind = T::kKind;
  f.type_name = T::kTypeName;
  f.summary = T::kSummary;
  f.params_schema = T::params_schema();
  f.create = &create<T>;
  f.capabilities = capabilities<T>();
  if constexpr (std::is_base_of_v<Vehicle, T>) f.api = vehicle_api<T>();
  if constexpr (std::is_base_of_v<Soil, T>) f.api = soil_api<T>();
  if constexpr (std::is_base_of_v<Coupler, T>) f.api = coupler_api<T>();
  return f;
}

#define RUMBLE_DETAIL_STR2(x) #x
#define RUMBLE_DETAIL_STR(x) RUMBLE_DETAIL_STR2(x)
/// What else a plugin is built with, appended to its build fingerprint (`rumble plugins` prints
/// it): a string literal starting with ", ", e.g. ", PETSc 3.18.5", defined by the plugin's build.
#ifndef RUMBLE_PLUGIN_BUILT_WITH
#define RUMBLE_PLUGIN_BUILT_WITH ""
#endif

template <class... Ts>
const rumble_plugin_descriptor* descriptor(const char* name, const char* version) {
  static const std::array<rumble_factory, sizeof...(Ts)> factories{factory<Ts>()...};
  static const rumble_plugin_descriptor d{
      sizeof(rumble_plugin_descriptor),
      RUMBLE_ABI_MAJOR,
      RUMBLE_ABI_MINOR,
      name,
      version,
      "g++/clang " __VERSION__ ", C++ " RUMBLE_DETAIL_STR(__cplusplus) RUMBLE_PLUGIN_BUILT_WITH,
      sizeof...(Ts),
      factories.data()};
  return &d;
}

}  // namespace detail
}  // namespace rumble

/// Exports the plugin's one entry point. NAME and VERSION are string literals; then the classes.
#define RUMBLE_PLUGIN(NAME, VERSION, ...)                                           \
  extern "C" __attribute__((visibility("default"))) const rumble_plugin_descriptor* \
  rumble_plugin_entry(void) {                                                       \
    return ::rumble::detail::descriptor<__VA_ARGS__>(NAME, VERSION);                \
  }

#endif  // RUMBLE_PLUGIN_HPP
