#include "plugin/instance.hpp"

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "core/logging.hpp"

namespace rumble {
namespace {

/// Every kind's table starts with struct_size, then the common functions.
const rumble_common_api* common_table(const ComponentType& type) {
  switch (type.kind) {
    case RUMBLE_KIND_VEHICLE:
      return &static_cast<const rumble_vehicle_api*>(type.factory->api)->common;
    case RUMBLE_KIND_SOIL:
      return &static_cast<const rumble_soil_api*>(type.factory->api)->common;
    case RUMBLE_KIND_COUPLER:
      return &static_cast<const rumble_coupler_api*>(type.factory->api)->common;
  }
  throw PluginLoadError("unknown component kind " + std::to_string(type.kind));
}

/// The 1.1 lifecycle table of a factory's function table, or null (1.0 plugin, none offered).
const rumble_lifecycle_api* lifecycle_table(const ComponentType& type) {
  if (type.abi_minor < 1) return nullptr;
  switch (type.kind) {
    case RUMBLE_KIND_VEHICLE:
      return static_cast<const rumble_vehicle_api*>(type.factory->api)->lifecycle;
    case RUMBLE_KIND_SOIL:
      return static_cast<const rumble_soil_api*>(type.factory->api)->lifecycle;
    case RUMBLE_KIND_COUPLER:
      return static_cast<const rumble_coupler_api*>(type.factory->api)->lifecycle;
  }
  return nullptr;
}

}  // namespace

Instance::Instance(const ComponentType& type, std::string label, const nlohmann::json& params,
                   const std::filesystem::path& scenario_dir)
    : type_(type),
      label_(std::move(label)),
      scenario_dir_(scenario_dir.string()),
      logger_(logger(std::string(kind_name(type.kind)) + "/" + type.type_name)) {
  host_.struct_size = sizeof(rumble_host);
  host_.abi_minor = RUMBLE_ABI_MINOR;
  host_.host_data = this;
  host_.log = &Instance::log_callback;
  host_.scenario_dir = scenario_dir_.c_str();
  host_.results_dir = results_dir_.c_str();
  host_.threads = 1;
  host_.progress = &Instance::progress_callback;
  common_ = common_table(type);
  lifecycle_ = lifecycle_table(type);
  const std::string text = params.dump();
  const char* error = nullptr;
  const rumble_status s = type.factory->create(text.c_str(), &host_, &handle_, &error);
  if (s != RUMBLE_OK || handle_ == nullptr) {
    throw ConfigError(label_ + ": " + kind_name(type.kind) + " type '" + type.type_name +
                      "' refused its params: " + (error != nullptr ? error : "no message") +
                      " (plugin " + type.library->path.string() + ")");
  }
}

Instance::~Instance() {
  if (handle_ != nullptr) common_->destroy(handle_);
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

void Instance::set_run_context(const std::filesystem::path& results_dir, unsigned threads) {
  results_dir_ = results_dir.string();
  host_.results_dir = results_dir_.c_str();
  host_.threads = std::max(1u, threads);
}

void Instance::finalize() {
  if (lifecycle_ != nullptr && lifecycle_->finalize != nullptr)
    check(lifecycle_->finalize(handle_), "finalize");
}

bool Instance::owns_checkpoints() const {
  return lifecycle_ != nullptr && lifecycle_->checkpoint_save != nullptr &&
         type_.capabilities.has(RUMBLE_CAP_OWN_CHECKPOINTS);
}
void Instance::checkpoint_save(std::uint32_t slot) {
  check(lifecycle_->checkpoint_save(handle_, slot), "checkpoint_save");
}
void Instance::checkpoint_restore(std::uint32_t slot) {
  check(lifecycle_->checkpoint_restore(handle_, slot), "checkpoint_restore");
}
void Instance::checkpoint_free(std::uint32_t slot) {
  if (lifecycle_->checkpoint_free != nullptr)
    check(lifecycle_->checkpoint_free(handle_, slot), "checkpoint_free");
}

rumble_status Instance::check(rumble_status status, const char* call) const {
  if (status == RUMBLE_OK) return status;
  const std::string what = common_->last_message(handle_);
  const std::string who =
      std::string(kind_name(type_.kind)) + " '" + type_.type_name + "' (" + label_ + ")";
  switch (status) {
    case RUMBLE_WARNING:
      logger_->warn("{}: {}", call, what);
      return status;
    case RUMBLE_DISCARD:
      throw Discarded(who + ": " + call + " refused: " + what);
    case RUMBLE_FATAL:
      throw RunError(who + ": " + call + " failed fatally: " + what);
    default:
      throw RunError(who + ": " + call + " failed: " + what);
  }
}

std::size_t Instance::state_size() const {
  std::uint64_t n = 0;
  check(common_->state_size(handle_, &n), "state_size");
  return static_cast<std::size_t>(n);
}

void Instance::save_state(std::vector<double>& buffer) const {
  if (buffer.empty()) buffer.resize(state_size());
  if (buffer.empty()) {
    throw RunError(std::string(kind_name(type_.kind)) + " '" + type_.type_name +
                   "' does not support save/restore, which this coupling scheme needs");
  }
  check(common_->save_state(handle_, buffer.data(), buffer.size()), "save_state");
}

void Instance::restore_state(const std::vector<double>& buffer) {
  check(common_->restore_state(handle_, buffer.data(), buffer.size()), "restore_state");
}

// ---------------------------------------------------------------- vehicle

VehicleInstance::VehicleInstance(const ComponentType& type, std::string label,
                                 const nlohmann::json& params,
                                 const std::filesystem::path& scenario_dir)
    : Instance(type, std::move(label), params, scenario_dir),
      api_(static_cast<const rumble_vehicle_api*>(type.factory->api)) {
  std::uint64_t n = 0;
  check(api_->dof_count(handle(), &n), "dof_count");
  n_dof_ = static_cast<std::size_t>(n);
  std::uint64_t n_wheels = 0;
  check(api_->wheels(handle(), nullptr, 0, &n_wheels), "wheels");
  wheels_.resize(static_cast<std::size_t>(n_wheels));
  check(api_->wheels(handle(), wheels_.data(), n_wheels, &n_wheels), "wheels");
  if (n_dof_ == 0 || wheels_.empty()) {
    throw ConfigError(this->label() + ": vehicle type '" + type.type_name + "' declares " +
                      std::to_string(n_dof_) + " DOFs and " + std::to_string(wheels_.size()) +
                      " wheels; a vehicle needs at least one of each");
  }
  n_outputs_ = output_names().size();
}

bool VehicleInstance::has_lengths() const {
  return this->type().abi_minor >= 1;  // the loader checked the 1.1 table is complete
}

void VehicleInstance::mass_matrix(const double* q, double* mass) const {
  if (has_lengths()) {
    check(api_->mass_matrix2(handle(), q, n_dof_, mass, n_dof_ * n_dof_), "mass_matrix");
  } else {
    check(api_->mass_matrix(handle(), q, mass), "mass_matrix");
  }
}
void VehicleInstance::forces(double t, const double* q, const double* qd, double* f) const {
  if (has_lengths()) {
    check(api_->forces2(handle(), t, q, qd, n_dof_, f), "forces");
  } else {
    check(api_->forces(handle(), t, q, qd, f), "forces");
  }
}
void VehicleInstance::wheel_kinematics(const double* q, double* z, double* jacobian) const {
  if (has_lengths()) {
    check(api_->wheel_kinematics2(handle(), q, n_dof_, z, wheels_.size(), jacobian),
          "wheel_kinematics");
  } else {
    check(api_->wheel_kinematics(handle(), q, z, jacobian), "wheel_kinematics");
  }
}
bool VehicleInstance::tangent(double t, const double* q, const double* qd, double* k,
                              double* c) const {
  if (has_lengths()) {
    if (!capabilities().has(RUMBLE_CAP_TANGENT) || api_->tangent2 == nullptr) return false;
    check(api_->tangent2(handle(), t, q, qd, n_dof_, k, c), "tangent");
    return true;
  }
  if (api_->tangent == nullptr) return false;
  try {
    check(api_->tangent(handle(), t, q, qd, k, c), "tangent");
  } catch (const Discarded&) {
    return false;
  }
  return true;
}
std::vector<std::string> VehicleInstance::output_names() const {
  std::vector<std::string> names;
  if (has_lengths() && api_->output_names2 != nullptr) {
    std::uint64_t n = 0;
    check(api_->output_names2(handle(), nullptr, 0, &n), "output_names");
    std::vector<const char*> raw(static_cast<std::size_t>(n), nullptr);
    check(api_->output_names2(handle(), raw.data(), n, &n), "output_names");
    for (const char* name : raw) names.emplace_back(name != nullptr ? name : "");
    return names;
  }
  if (api_->output_names == nullptr) return names;
  const std::string all = api_->output_names(handle());
  std::size_t start = 0;
  while (start < all.size()) {
    const std::size_t end = all.find(';', start);
    names.push_back(all.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return names;
}
void VehicleInstance::outputs(double t, const double* q, const double* qd, double* values) const {
  if (has_lengths() && api_->outputs2 != nullptr) {
    check(api_->outputs2(handle(), t, q, qd, n_dof_, values, n_outputs_), "outputs");
  } else if (api_->outputs != nullptr) {
    check(api_->outputs(handle(), t, q, qd, values), "outputs");
  }
}

// ---------------------------------------------------------------- soil

SoilInstance::SoilInstance(const ComponentType& type, std::string label,
                           const nlohmann::json& params, const std::filesystem::path& scenario_dir)
    : Instance(type, std::move(label), params, scenario_dir),
      api_(static_cast<const rumble_soil_api*>(type.factory->api)) {}

void SoilInstance::accept_layout(const std::vector<rumble_footprint>& footprints) {
  try {
    check(api_->accept_layout(handle(), footprints.data(), footprints.size()), "accept_layout");
  } catch (const std::exception& e) {
    throw ConfigError(std::string(e.what()) +
                      "; the layout comes from /track/sleepers (count, spacing, footprint)");
  }
}
void SoilInstance::initialize(double t0, const std::vector<double>& static_force,
                              std::vector<double>& u) {
  u.resize(static_force.size());
  check(api_->initialize(handle(), t0, static_force.data(), u.data(), u.size()), "initialize");
}
void SoilInstance::advance(double t, double H, const rumble_waveform& force) {
  check(api_->advance(handle(), t, H, &force), "advance");
}
void SoilInstance::motion(double* u, double* v, std::size_t n) const {
  check(api_->motion(handle(), u, v, n), "motion");
}
bool SoilInstance::frequency_response(double f_hz, std::size_t n,
                                      std::vector<std::complex<double>>& receptance) {
  if (api_->frequency_response == nullptr) return false;
  if (type().abi_minor >= 1 && !capabilities().has(RUMBLE_CAP_FREQUENCY_RESPONSE)) return false;
  re_.resize(n * n);
  im_.resize(n * n);
  try {
    check(api_->frequency_response(handle(), f_hz, re_.data(), im_.data(), n),
          "frequency_response");
  } catch (const Discarded&) {
    return false;
  }
  receptance.resize(n * n);
  for (std::size_t k = 0; k < n * n; ++k) receptance[k] = {re_[k], im_[k]};
  return true;
}
bool SoilInstance::set_receivers(const std::vector<rumble_receiver>& receivers) {
  if (api_->set_receivers == nullptr) return false;
  if (type().abi_minor >= 1 && !capabilities().has(RUMBLE_CAP_SURFACE_RECEIVERS)) return false;
  try {
    check(api_->set_receivers(handle(), receivers.data(), receivers.size()), "set_receivers");
  } catch (const Discarded&) {
    return false;
  }
  return true;
}
void SoilInstance::receiver_velocity(double* v, std::size_t n) const {
  check(api_->receiver_velocity(handle(), v, n), "receiver_velocity");
}
bool SoilInstance::set_probes(const std::vector<rumble_probe>& probes, double sample_interval) {
  if (type().abi_minor < 1 || !capabilities().has(RUMBLE_CAP_RECEIVERS)) return false;
  check(api_->set_probes(handle(), probes.data(), probes.size(), sample_interval), "set_probes");
  n_probes_ = probes.size();
  return true;
}
void SoilInstance::take_probe_samples(std::vector<double>& times, std::vector<double>& values) {
  if (n_probes_ == 0) return;
  std::uint64_t n = 0;
  check(api_->probe_samples(handle(), nullptr, nullptr, 0, &n), "probe_samples");
  if (n == 0) return;
  const std::size_t t0 = times.size(), v0 = values.size();
  times.resize(t0 + n);
  values.resize(v0 + n * n_probes_ * RUMBLE_PROBE_VALUES);
  std::uint64_t written = 0;
  check(api_->probe_samples(handle(), times.data() + t0, values.data() + v0, n, &written),
        "probe_samples");
  times.resize(t0 + written);
  values.resize(v0 + written * n_probes_ * RUMBLE_PROBE_VALUES);
}
bool SoilInstance::write_fields(double t, const std::filesystem::path& path) {
  if (type().abi_minor < 1 || !capabilities().has(RUMBLE_CAP_FIELD_OUTPUT)) return false;
  check(api_->write_fields(handle(), t, path.c_str()), "write_fields");
  return true;
}
bool SoilInstance::linear_matrix(rumble_matrix which, Eigen::SparseMatrix<double>& out) {
  if (type().abi_minor < 1 || !capabilities().has(RUMBLE_CAP_LINEAR_MATRICES)) return false;
  rumble_csc csc{};
  check(api_->linear_matrix(handle(), which, &csc), "linear_matrix");
  const std::uint64_t rows = csc.rows, cols = csc.cols, nnz = csc.nnz;
  std::vector<std::int64_t> col_ptr(cols + 1), row_index(nnz);
  std::vector<double> values(nnz);
  csc.col_ptr = col_ptr.data();
  csc.row_index = row_index.data();
  csc.values = values.data();
  check(api_->linear_matrix(handle(), which, &csc), "linear_matrix");
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
  if (type().abi_minor < 1 || !capabilities().has(RUMBLE_CAP_WAVE_SPEEDS)) return false;
  check(api_->wave_speeds(handle(), &c_s_min, &c_r_min), "wave_speeds");
  return true;
}

// ---------------------------------------------------------------- coupler

CouplerInstance::CouplerInstance(const ComponentType& type, std::string label,
                                 const nlohmann::json& params,
                                 const std::filesystem::path& scenario_dir)
    : Instance(type, std::move(label), params, scenario_dir),
      api_(static_cast<const rumble_coupler_api*>(type.factory->api)) {}

rumble_status CouplerInstance::run(const rumble_cosim_host& host, double t0, double t_end, double H,
                                   std::string& message) {
  const rumble_status s = api_->run(handle(), &host, t0, t_end, H);
  message = s == RUMBLE_OK ? "" : common().last_message(handle());
  return s;
}

}  // namespace rumble
