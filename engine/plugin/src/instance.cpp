#include "plugin/instance.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <optional>

#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "core/logging.hpp"
#include "core/number_text.hpp"
#include "parallel/mirror_transport.hpp"
#include "parallel/mpi_session.hpp"

namespace rumble {
namespace {

std::atomic<int> planned_ranks{0};  // set_planned_ranks

/// Every kind's table starts with struct_size, then the common functions.
const rumble_common_api* common_table(const ComponentType& type) {
  switch (type.kind) {
    case RUMBLE_KIND_VEHICLE:
      return &static_cast<const rumble_vehicle_api*>(type.factory().api)->common;
    case RUMBLE_KIND_SOIL:
      return &static_cast<const rumble_soil_api*>(type.factory().api)->common;
    case RUMBLE_KIND_COUPLER:
      return &static_cast<const rumble_coupler_api*>(type.factory().api)->common;
  }
  throw PluginLoadError("unknown component kind " + std::to_string(type.kind));
}

/// Throws for a checkpoint slot that does not exist.
void check_checkpoint_slot(std::uint32_t slot) {
  if (slot >= RUMBLE_CHECKPOINT_SLOTS) {
    throw RunError("checkpoint slot " + std::to_string(slot) + " does not exist (slots 0.." +
                   std::to_string(RUMBLE_CHECKPOINT_SLOTS - 1) + ")");
  }
}

/// The index of the first value that is not finite (NaN, +-inf), if any (none in no array).
std::optional<std::size_t> first_not_finite(const double* v, std::size_t n) {
  if (v == nullptr) return std::nullopt;
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) return i;
  return std::nullopt;
}

bool all_finite(const double* v, std::size_t n) {
  return !first_not_finite(v, n);
}

}  // namespace

Instance::Instance(const ComponentType& type, std::string label, const nlohmann::json& params,
                   const std::filesystem::path& scenario_dir)
    : type_(type),
      label_(std::move(label)),
      // "x.json" has the directory "": the current one, which plugins should read as ".".
      scenario_dir_(scenario_dir.empty() ? std::string(".") : scenario_dir.string()),
      logger_(logger(std::string(kind_name(type.kind)) + "/" + type.type_name)),
      common_(common_table(type)),
      lifecycle_(abi::lifecycle_of(type)),
      checkpoints_(*common_, lifecycle_, type.capabilities) {
  host_.struct_size = sizeof(rumble_host);
  host_.abi_minor = RUMBLE_ABI_MINOR;
  host_.host_data = this;
  host_.log = &Instance::log_callback;
  host_.scenario_dir = scenario_dir_.c_str();
  host_.results_dir = results_dir_.c_str();
  host_.threads = 1;
  host_.progress = &Instance::progress_callback;
  host_.communicator = &Instance::communicator_callback;
  host_.planned_ranks = planned_ranks.load();
  const bool everywhere = type.kind == RUMBLE_KIND_SOIL &&
                          type.capabilities.has(RUMBLE_CAP_DISTRIBUTED) && parallel::running() &&
                          parallel::world_size() > 1 && parallel::world_rank() == 0;
  if (everywhere) {
    create_everywhere(params);
  } else {
    warn_idle_ranks();
    create_here(params.dump());
  }
}

void set_planned_ranks(int ranks) {
  planned_ranks = ranks < 0 ? 0 : ranks;
}

void Instance::warn_idle_ranks() const {
  static std::atomic<bool> said{false};  // once per process: validation builds the soil too
  if (type_.kind != RUMBLE_KIND_SOIL || !parallel::running() || parallel::world_size() < 2 ||
      parallel::world_rank() != 0 || said.exchange(true))
    return;
  logger_->warn(
      "{}: launched on {} MPI ranks, but soil type '{}' runs on one (it does not declare the "
      "'distributed' capability): the other {} wait idle; run it without mpirun, or give "
      "mpirun a study, whose runs it shares out (docs/decisions/0012-distributed-soil.md)",
      label_, parallel::world_size(), type_.type_name,
      parallel::world_size() == 2 ? std::string("rank")
                                  : std::to_string(parallel::world_size() - 1) + " ranks");
}

void Instance::create_here(const std::string& params_text) {
  const char* error = nullptr;
  rumble_status s = RUMBLE_ERROR;
  try {  // a plugin written against abi.h directly may let an exception escape
    s = type_.factory().create(params_text.c_str(), &host_, &handle_, &error);
  } catch (const std::exception& e) {
    throw_escaped("create", e.what());
  } catch (...) {
    throw_escaped("create", "an exception not derived from std::exception");
  }
  if (s != RUMBLE_OK || handle_ == nullptr) {
    const std::string said = error != nullptr && *error != '\0' ? error : "no message";
    throw ParamsRefused(label_ + ": " + kind_name(type_.kind) + " type '" + type_.type_name +
                            "' refused its params: " + said + " (plugin " +
                            type_.library->path.string() + ")",
                        said);
  }
}

void Instance::create_everywhere(const nlohmann::json& params) {
  static std::atomic<std::uint64_t> next_id{1};
  mirror_id_ = next_id++;
  const std::string text = params.dump();
  mirror::Writer w;
  w.put(mirror::Service::kSoil).put(mirror::Call::kCreate).put(mirror_id_);
  w.put_text(type_.library->path.string()).put_text(type_.type_name).put_text(label_);
  w.put_text(text).put_text(scenario_dir_);
  try {
    run_mirrored(w, [&] { create_here(text); });
  } catch (...) {
    destroy_everywhere();  // the ranks where it was created
    throw;
  }
}

void Instance::destroy_everywhere() noexcept {
  mirror::Writer w;
  w.put(mirror::Service::kSoil).put(mirror::Call::kDestroy).put(mirror_id_);
  try {
    run_mirrored(w, [&] {
      if (handle_ != nullptr) common_->destroy(handle_);
      handle_ = nullptr;
    });
  } catch (const std::exception& e) {
    logger_->error("{}: destroying it: {}", who(), e.what());
  }
}

void Instance::run_mirrored(const mirror::Writer& w, const std::function<void()>& body) const {
  parallel::send_to_servers(w.bytes());
  std::exception_ptr failed;
  std::string mine;
  in_mirrored_call_ = true;
  try {
    body();
  } catch (const std::exception& e) {
    failed = std::current_exception();
    mine = e.what();
  } catch (...) {
    failed = std::current_exception();
    mine = "an exception not derived from std::exception";
  }
  in_mirrored_call_ = false;
  const std::string first = parallel::first_failure(mine);
  if (failed) std::rethrow_exception(failed);
  if (!first.empty()) throw RunError("MPI " + first);  // "MPI rank 1: soil 'x' (/soil): ..."
}

Instance::~Instance() {
  if (mirror_id_ != 0) {
    destroy_everywhere();
  } else if (handle_ != nullptr) {
    common_->destroy(handle_);
  }
}

void Instance::log_callback(void* host_data, int32_t level, const char* message) {
  const auto* self = static_cast<const Instance*>(host_data);
  switch (level) {
    case RUMBLE_LOG_DEBUG:
      self->logger_->debug("{}", message);
      break;
    case RUMBLE_LOG_WARN:
      self->logger_->warn("{}", message);
      break;
    case RUMBLE_LOG_ERROR:
      self->logger_->error("{}", message);
      break;
    default:
      self->logger_->info("{}", message);
  }
}

int32_t Instance::progress_callback(void* /*host_data*/, double /*fraction*/) {
  return interrupt_requested() ? 1 : 0;
}

rumble_status Instance::communicator_callback(void* host_data, int64_t* fortran_handle,
                                              int32_t* rank, int32_t* size) {
  auto* self = static_cast<Instance*>(host_data);
  try {
    if (self->communicator_ == nullptr) {
      const bool world = self->type_.capabilities.has(RUMBLE_CAP_DISTRIBUTED);
      self->communicator_ = std::make_unique<parallel::Communicator>(world);
    }
    *fortran_handle = self->communicator_->fortran_handle();
    *rank = self->communicator_->rank();
    *size = self->communicator_->size();
    return RUMBLE_OK;
  } catch (const std::exception& e) {
    self->logger_->error("{}", e.what());
    *size = 0;
    return RUMBLE_ERROR;
  }
}

void Instance::set_run_context(const std::filesystem::path& results_dir, unsigned threads) {
  set_results_dir(results_dir);
  grant_threads(threads);
}

void Instance::set_results_dir(const std::filesystem::path& results_dir) {
  results_dir_ = results_dir.string();
  host_.results_dir = results_dir_.c_str();
  mirror_host_context();
}

void Instance::grant_threads(unsigned threads) {
  host_.threads = std::max(1u, threads);
  mirror_host_context();
}

void Instance::mirror_host_context() const {
  const auto encode = [&](mirror::Writer& w) { w.put_text(results_dir_).put(host_.threads); };
  mirrored(mirror::Call::kHostContext, encode, [] {});
}

void Instance::finalize() {
  if (lifecycle_ == nullptr || lifecycle_->finalize == nullptr) return;
  mirrored(
      mirror::Call::kFinalize, [](mirror::Writer&) {},
      [&] { call("finalize", [&] { return lifecycle_->finalize(handle_); }); });
}

bool Instance::can_checkpoint() const {
  if (checkpoints_.plugin_held()) return true;
  return mirrored(
      mirror::Call::kCanCheckpoint, [](mirror::Writer&) {},
      [&] {
        std::uint64_t n = 0;
        call("state_size", [&] { return checkpoints_.state_size(handle_, &n); });
        return n > 0;
      });
}
void Instance::checkpoint_save(std::uint32_t slot) {
  check_checkpoint_slot(slot);
  mirrored(
      mirror::Call::kCheckpointSave, [&](mirror::Writer& w) { w.put(slot); },
      [&] {
        if (!can_checkpoint()) {
          throw RunError(std::string(kind_name(type_.kind)) + " '" + type_.type_name +
                         "' does not support save/restore, which this coupling scheme needs");
        }
        call("checkpoint_save", [&] { return checkpoints_.save(handle_, slot); });
      });
}
void Instance::checkpoint_restore(std::uint32_t slot) {
  check_checkpoint_slot(slot);
  if (!checkpoints_.restorable(slot))
    throw RunError("restore from checkpoint slot " + std::to_string(slot) + " never saved");
  mirrored(
      mirror::Call::kCheckpointRestore, [&](mirror::Writer& w) { w.put(slot); },
      [&] { call("checkpoint_restore", [&] { return checkpoints_.restore(handle_, slot); }); });
}
void Instance::checkpoint_free(std::uint32_t slot) {
  check_checkpoint_slot(slot);
  mirrored(
      mirror::Call::kCheckpointFree, [&](mirror::Writer& w) { w.put(slot); },
      [&] { call("checkpoint_free", [&] { return checkpoints_.release(handle_, slot); }); });
}

std::string Instance::who() const {
  return std::string(kind_name(type_.kind)) + " '" + type_.type_name + "' (" + label_ + ")";
}

std::string Instance::last_message() const {
  // NULL is what a C plugin returns when it has nothing to say; std::string(NULL) is undefined.
  const char* m = handle_ != nullptr ? common_->last_message(handle_) : nullptr;
  return m != nullptr && *m != '\0' ? std::string(m) : std::string("no message");
}

void Instance::throw_escaped(const char* call, const std::string& what) const {
  throw RunError(who() + ": " + call + " let an exception escape through the C interface: " + what +
                 " (plugin " + type_.library->path.string() +
                 "); a plugin must catch its exceptions and return a status (the SDK's "
                 "RUMBLE_PLUGIN() does this); report it to the plugin's author");
}

void Instance::throw_not_finite(const char* call, const std::string& what, std::size_t index,
                                double value, bool inputs_finite) const {
  const std::string got = std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf");
  if (!inputs_finite) {
    throw RunError(who() + ": " + call + " returned a " + what + " that is not finite (" + got +
                   " at " + std::to_string(index) +
                   ") from inputs that were not finite either: the solution diverged before "
                   "this call; reduce time.macro_step or track.integrator.micro_step, or use the "
                   "implicit coupler");
  }
  throw RunError(who() + ": " + call + " returned a " + what + " that is not finite (" + got +
                 " at " + std::to_string(index) + ") from finite inputs (plugin " +
                 type_.library->path.string() +
                 "): a defect or an instability inside the plugin; check its params, or report "
                 "it to the plugin's author");
}

rumble_status Instance::check(rumble_status status, const char* call) const {
  if (status == RUMBLE_OK) return status;
  const std::string what = last_message();
  const std::string who = this->who();
  switch (status) {
    case RUMBLE_WARNING:
      logger_->warn("{}: {}", call, what);
      return status;
    case RUMBLE_DISCARD:
      if (!may_refuse())  // a coupler may have kept no checkpoint to put the other side back
        throw RunError(who + ": " + call + " refused a step (" + what +
                       ") although its type declares it never does (capability never_refuses, "
                       "ABI 1.7); the plugin's author must drop the declaration or the refusal");
      throw Discarded(who + ": " + call + " refused: " + what);
    case RUMBLE_FATAL:
      throw RunError(who + ": " + call + " failed fatally: " + what);
    default:
      throw RunError(who + ": " + call + " failed: " + what);
  }
}

// ---------------------------------------------------------------- vehicle

VehicleInstance::VehicleInstance(const ComponentType& type, std::string label,
                                 const nlohmann::json& params,
                                 const std::filesystem::path& scenario_dir)
    : Instance(type, std::move(label), params, scenario_dir), calls_(type) {
  std::uint64_t n = 0;
  call("dof_count", [&] { return calls_.dof_count(handle(), &n); });
  n_dof_ = static_cast<std::size_t>(n);
  std::uint64_t n_wheels = 0;
  call("wheels", [&] { return calls_.wheels(handle(), nullptr, 0, &n_wheels); });
  wheels_.resize(static_cast<std::size_t>(n_wheels));
  call("wheels", [&] { return calls_.wheels(handle(), wheels_.data(), n_wheels, &n_wheels); });
  for (std::size_t w = 0; w < wheels_.size(); ++w) {
    if (!std::isfinite(wheels_[w].offset))
      throw_not_finite("wheels", "wheel offset", w, wheels_[w].offset);
    if (!std::isfinite(wheels_[w].radius))
      throw_not_finite("wheels", "wheel radius", w, wheels_[w].radius);
  }
  if (n_dof_ == 0 || wheels_.empty()) {
    throw ConfigError(this->label() + ": vehicle type '" + type.type_name + "' declares " +
                      std::to_string(n_dof_) + " DOFs and " + std::to_string(wheels_.size()) +
                      " wheels; a vehicle needs at least one of each");
  }
  n_outputs_ = output_names().size();
}

void VehicleInstance::mass_matrix(const double* q, double* mass) const {
  call("mass_matrix",
       [&] { return calls_.mass_matrix2(handle(), q, n_dof_, mass, n_dof_ * n_dof_); });
  if (const auto bad = first_not_finite(mass, n_dof_ * n_dof_))
    throw_not_finite("mass_matrix", "mass matrix entry", *bad, mass[*bad], all_finite(q, n_dof_));
}
void VehicleInstance::forces(double t, const double* q, const double* qd, double* f) const {
  call("forces", [&] { return calls_.forces2(handle(), t, q, qd, n_dof_, f); });
  if (const auto bad = first_not_finite(f, n_dof_))
    throw_not_finite("forces", "generalized force", *bad, f[*bad],
                     all_finite(q, n_dof_) && all_finite(qd, n_dof_));
}
void VehicleInstance::wheel_kinematics(const double* q, double* z, double* jacobian) const {
  call("wheel_kinematics",
       [&] { return calls_.wheel_kinematics2(handle(), q, n_dof_, z, wheels_.size(), jacobian); });
  if (const auto bad = first_not_finite(z, wheels_.size()))
    throw_not_finite("wheel_kinematics", "wheel position", *bad, z[*bad], all_finite(q, n_dof_));
  if (jacobian == nullptr) return;
  if (const auto bad = first_not_finite(jacobian, wheels_.size() * n_dof_))
    throw_not_finite("wheel_kinematics", "Jacobian entry", *bad, jacobian[*bad],
                     all_finite(q, n_dof_));
}
bool VehicleInstance::tangent(double t, const double* q, const double* qd, double* k,
                              double* c) const {
  if (!calls_.offers_tangent()) return false;
  try {  // DISCARD: "not offered", as a 1.0 vehicle answered (abi.h, rumble_status)
    call("tangent", [&] { return calls_.tangent2(handle(), t, q, qd, n_dof_, k, c); });
  } catch (const Discarded&) {
    return false;
  }
  return true;
}
std::vector<std::string> VehicleInstance::output_names() const {
  std::vector<std::string> names;
  call("output_names", [&] { return calls_.output_names2(handle(), names); });
  return names;
}
void VehicleInstance::outputs(double t, const double* q, const double* qd, double* values) const {
  call("outputs", [&] { return calls_.outputs2(handle(), t, q, qd, n_dof_, values, n_outputs_); });
}

// ---------------------------------------------------------------- soil

SoilInstance::SoilInstance(const ComponentType& type, std::string label,
                           const nlohmann::json& params, const std::filesystem::path& scenario_dir)
    : Instance(type, std::move(label), params, scenario_dir), api_(abi::current_soil_table(type)) {}

void SoilInstance::accept_layout(const std::vector<rumble_footprint>& footprints) {
  try {
    mirrored(
        mirror::Call::kAcceptLayout,
        [&](mirror::Writer& w) { w.put_array(footprints.data(), footprints.size()); },
        [&] {
          call("accept_layout",
               [&] { return api_.accept_layout(handle(), footprints.data(), footprints.size()); });
        });
  } catch (const std::exception& e) {
    throw ConfigError(std::string(e.what()) +
                      "; the layout comes from /track/sleepers (count, spacing, footprint)");
  }
}
void SoilInstance::initialize(double t0, const std::vector<double>& static_force,
                              std::vector<double>& u) {
  u.resize(static_force.size());
  mirrored(
      mirror::Call::kInitialize,
      [&](mirror::Writer& w) { w.put(t0).put_array(static_force.data(), static_force.size()); },
      [&] {
        call("initialize", [&] {
          return api_.initialize(handle(), t0, static_force.data(), u.data(), u.size());
        });
      });
  if (const auto bad = first_not_finite(u.data(), u.size()))
    throw_not_finite("initialize", "static displacement", *bad, u[*bad],
                     all_finite(static_force.data(), static_force.size()));
}
void SoilInstance::advance(double t, double H, const rumble_waveform& force) {
  // The forces come from the engine's side (the track, or a reduced soil's recorded forces):
  // when they are not finite the coupled solution has diverged, whatever the soil does next.
  const std::size_t n_coeff = (force.order + 1) * force.n;
  if (const auto bad = first_not_finite(force.coeff, n_coeff)) {
    throw RunError("simulation diverged at t = " + number_text(t) +
                   " s: the footprint force given to " + who() + " is not finite (footprint " +
                   std::to_string(*bad % force.n) +
                   "); reduce time.macro_step or track.integrator.micro_step, or use the "
                   "implicit coupler");
  }
  const auto encode = [&](mirror::Writer& w) {
    w.put(t).put(H).put(force.order).put_array(force.coeff, n_coeff);
  };
  mirrored(mirror::Call::kAdvance, encode,
           [&] { call("advance", [&] { return api_.advance(handle(), t, H, &force); }); });
}
void SoilInstance::motion(double* u, double* v, std::size_t n) const {
  mirrored(
      mirror::Call::kMotion, [&](mirror::Writer& w) { w.put(static_cast<std::uint64_t>(n)); },
      [&] { call("motion", [&] { return api_.motion(handle(), u, v, n); }); });
  // Every input (the forces) was checked finite by advance, so a value that is not finite is
  // the plugin's own (the divergence monitor would otherwise blame the coupling for it).
  if (const auto bad = first_not_finite(u, n))
    throw_not_finite("motion", "displacement", *bad, u[*bad]);
  if (const auto bad = first_not_finite(v, n))
    throw_not_finite("motion", "velocity", *bad, v[*bad]);
}
bool SoilInstance::frequency_response(double f_hz, std::size_t n,
                                      std::vector<std::complex<double>>& receptance) {
  if (api_.frequency_response == nullptr || !capabilities().has(RUMBLE_CAP_FREQUENCY_RESPONSE))
    return false;
  re_.resize(n * n);
  im_.resize(n * n);
  try {
    mirrored(
        mirror::Call::kFrequencyResponse,
        [&](mirror::Writer& w) { w.put(f_hz).put(static_cast<std::uint64_t>(n)); },
        [&] {
          call("frequency_response",
               [&] { return api_.frequency_response(handle(), f_hz, re_.data(), im_.data(), n); });
        });
  } catch (const Discarded&) {
    return false;
  }
  if (const auto bad = first_not_finite(re_.data(), n * n))
    throw_not_finite("frequency_response", "receptance (real part)", *bad, re_[*bad]);
  if (const auto bad = first_not_finite(im_.data(), n * n))
    throw_not_finite("frequency_response", "receptance (imaginary part)", *bad, im_[*bad]);
  receptance.resize(n * n);
  for (std::size_t k = 0; k < n * n; ++k) receptance[k] = {re_[k], im_[k]};
  return true;
}
bool SoilInstance::set_receivers(const std::vector<rumble_receiver>& receivers) {
  if (api_.set_receivers == nullptr || !capabilities().has(RUMBLE_CAP_SURFACE_RECEIVERS))
    return false;
  try {
    mirrored(
        mirror::Call::kSetReceivers,
        [&](mirror::Writer& w) { w.put_array(receivers.data(), receivers.size()); },
        [&] {
          call("set_receivers",
               [&] { return api_.set_receivers(handle(), receivers.data(), receivers.size()); });
        });
  } catch (const Discarded&) {
    return false;
  }
  return true;
}
void SoilInstance::receiver_velocity(double* v, std::size_t n) const {
  mirrored(
      mirror::Call::kReceiverVelocity,
      [&](mirror::Writer& w) { w.put(static_cast<std::uint64_t>(n)); },
      [&] { call("receiver_velocity", [&] { return api_.receiver_velocity(handle(), v, n); }); });
  if (const auto bad = first_not_finite(v, n))
    throw_not_finite("receiver_velocity", "receiver velocity", *bad, v[*bad]);
}
bool SoilInstance::set_probes(const std::vector<rumble_probe>& probes, double sample_interval) {
  if (api_.set_probes == nullptr || !capabilities().has(RUMBLE_CAP_RECEIVERS)) return false;
  const auto encode = [&](mirror::Writer& w) {
    w.put(sample_interval).put(static_cast<std::uint64_t>(probes.size()));
    for (const rumble_probe& p : probes)
      w.put_text(p.name != nullptr ? p.name : "").put(p.x).put(p.y).put(p.depth);
  };
  mirrored(mirror::Call::kSetProbes, encode, [&] {
    call("set_probes",
         [&] { return api_.set_probes(handle(), probes.data(), probes.size(), sample_interval); });
  });
  n_probes_ = probes.size();
  return true;
}
void SoilInstance::take_probe_samples(std::vector<double>& times, std::vector<double>& values) {
  if (n_probes_ == 0) return;
  mirrored(
      mirror::Call::kTakeProbeSamples, [](mirror::Writer&) {},
      [&] { take_probe_samples_here(times, values); });
}
void SoilInstance::take_probe_samples_here(std::vector<double>& times,
                                           std::vector<double>& values) {
  std::uint64_t n = 0;
  call("probe_samples", [&] { return api_.probe_samples(handle(), nullptr, nullptr, 0, &n); });
  if (n == 0) return;
  const std::size_t t0 = times.size(), v0 = values.size();
  times.resize(t0 + n);
  values.resize(v0 + n * n_probes_ * RUMBLE_PROBE_VALUES);
  std::uint64_t written = 0;
  call("probe_samples", [&] {
    return api_.probe_samples(handle(), times.data() + t0, values.data() + v0, n, &written);
  });
  times.resize(t0 + written);
  values.resize(v0 + written * n_probes_ * RUMBLE_PROBE_VALUES);
}
std::optional<SoilInstance::ProbeResolution> SoilInstance::probe_resolution() const {
  if (n_probes_ == 0 || api_.probe_resolution == nullptr) return std::nullopt;
  ProbeResolution r;
  r.f_hz.assign(n_probes_, 0.0);
  const char* rule = nullptr;
  mirrored(
      mirror::Call::kProbeResolution, [](mirror::Writer&) {},
      [&] {
        call("probe_resolution",
             [&] { return api_.probe_resolution(handle(), r.f_hz.data(), n_probes_, &rule); });
      });
  for (std::size_t p = 0; p < n_probes_; ++p) {
    if (!std::isfinite(r.f_hz[p]))
      throw_not_finite("probe_resolution", "resolved frequency", p, r.f_hz[p]);
    if (r.f_hz[p] < 0.0)
      throw RunError(who() + ": probe_resolution returned " + std::to_string(r.f_hz[p]) +
                     " Hz for probe " + std::to_string(p) +
                     ", below 0 (0 says the soil cannot tell): a defect of the plugin " +
                     type().library->path.string());
  }
  if (rule == nullptr) return std::nullopt;  // the soil does not say
  r.rule = rule;
  return r;
}
std::optional<SoilInstance::Size> SoilInstance::size() const {
  if (api_.size == nullptr) return std::nullopt;
  Size size;
  mirrored(
      mirror::Call::kSize, [](mirror::Writer&) {},
      [&] { call("size", [&] { return api_.size(handle(), &size.dofs, &size.peak_bytes); }); });
  if (!std::isfinite(size.peak_bytes)) throw_not_finite("size", "peak memory", 0, size.peak_bytes);
  if (size.peak_bytes < 0.0)
    throw RunError(who() + ": size returned a peak memory of " + std::to_string(size.peak_bytes) +
                   " bytes, below 0 (0 says the soil cannot tell): a defect of the plugin " +
                   type().library->path.string());
  return size;
}

void SoilInstance::statics_done() {
  if (api_.statics_done == nullptr) return;
  mirrored(
      mirror::Call::kStaticsDone, [](mirror::Writer&) {},
      [&] { call("statics_done", [&] { return api_.statics_done(handle()); }); });
}

bool SoilInstance::offers_fields() const {
  return api_.write_fields != nullptr && capabilities().has(RUMBLE_CAP_FIELD_OUTPUT);
}

int SoilInstance::field_pieces() const {
  return mirror_id() != 0 ? parallel::world_size() : 1;
}

bool SoilInstance::write_fields(double t, const std::filesystem::path& path) {
  if (!offers_fields()) return false;
  mirrored(
      mirror::Call::kWriteFields, [&](mirror::Writer& w) { w.put(t).put_text(path.string()); },
      [&] { call("write_fields", [&] { return api_.write_fields(handle(), t, path.c_str()); }); });
  return true;
}
bool SoilInstance::linear_matrix(rumble_matrix which, Eigen::SparseMatrix<double>& out) {
  if (api_.linear_matrix == nullptr || !capabilities().has(RUMBLE_CAP_LINEAR_MATRICES))
    return false;
  return mirrored(
      mirror::Call::kLinearMatrix, [&](mirror::Writer& w) { w.put(which); },
      [&] { return linear_matrix_here(which, out); });
}
bool SoilInstance::linear_matrix_here(rumble_matrix which, Eigen::SparseMatrix<double>& out) {
  rumble_csc csc{};
  call("linear_matrix", [&] { return api_.linear_matrix(handle(), which, &csc); });
  const std::uint64_t rows = csc.rows, cols = csc.cols, nnz = csc.nnz;
  std::vector<std::int64_t> col_ptr(cols + 1), row_index(nnz);
  std::vector<double> values(nnz);
  csc.col_ptr = col_ptr.data();
  csc.row_index = row_index.data();
  csc.values = values.data();
  call("linear_matrix", [&] { return api_.linear_matrix(handle(), which, &csc); });
  const auto defect = [&](const std::string& what) {
    return RunError("soil '" + type_name() + "' (" + label() + "): linear_matrix " +
                    std::to_string(static_cast<int>(which)) +
                    " is not a valid CSC matrix: " + what);
  };
  if (csc.rows != rows || csc.cols != cols || csc.nnz != nnz)
    throw defect("its size changed between the size query and the fill");
  if (col_ptr[0] != 0 || col_ptr[cols] != static_cast<std::int64_t>(nnz))
    throw defect("col_ptr must run from 0 to nnz");
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(nnz);
  for (std::uint64_t j = 0; j < cols; ++j) {
    if (col_ptr[j + 1] < col_ptr[j])
      throw defect("col_ptr decreases at column " + std::to_string(j));
    for (std::int64_t k = col_ptr[j]; k < col_ptr[j + 1]; ++k) {
      const std::int64_t r = row_index[static_cast<std::size_t>(k)];
      const double v = values[static_cast<std::size_t>(k)];
      if (r < 0 || static_cast<std::uint64_t>(r) >= rows)
        throw defect("row index " + std::to_string(r) + " out of range in column " +
                     std::to_string(j));
      if (k > col_ptr[j] && r <= row_index[static_cast<std::size_t>(k - 1)])
        throw defect("rows not sorted (or repeated) in column " + std::to_string(j));
      if (!std::isfinite(v)) throw defect("a value is not finite in column " + std::to_string(j));
      entries.emplace_back(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(j), v);
    }
  }
  out.resize(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
  out.setFromTriplets(entries.begin(), entries.end());
  return true;
}

bool SoilInstance::wave_speeds(double& c_s_min, double& c_r_min) const {
  if (api_.wave_speeds == nullptr || !capabilities().has(RUMBLE_CAP_WAVE_SPEEDS)) return false;
  mirrored(
      mirror::Call::kWaveSpeeds, [](mirror::Writer&) {},
      [&] { call("wave_speeds", [&] { return api_.wave_speeds(handle(), &c_s_min, &c_r_min); }); });
  if (!std::isfinite(c_s_min)) throw_not_finite("wave_speeds", "shear wave speed", 0, c_s_min);
  if (!std::isfinite(c_r_min)) throw_not_finite("wave_speeds", "Rayleigh wave speed", 0, c_r_min);
  return true;
}

// ---------------------------------------------------------------- coupler

CouplerInstance::CouplerInstance(const ComponentType& type, std::string label,
                                 const nlohmann::json& params,
                                 const std::filesystem::path& scenario_dir)
    : Instance(type, std::move(label), params, scenario_dir),
      api_(abi::current_coupler_table(type)) {}

rumble_status CouplerInstance::run(const rumble_cosim_host& host, double t0, double t_end, double H,
                                   std::string& message) {
  rumble_status s = RUMBLE_ERROR;
  try {
    s = api_.run(handle(), &host, t0, t_end, H);
  } catch (const std::exception& e) {
    throw_escaped("run", e.what());
  } catch (...) {
    throw_escaped("run", "an exception not derived from std::exception");
  }
  message = s == RUMBLE_OK ? "" : last_message();
  return s;
}

}  // namespace rumble
