#include "plugin/abi_adapter.hpp"

#include <algorithm>
#include <cstring>

namespace rumble::abi {
namespace {

/// End of FIELD in TYPE: the size a table must have to hold it.
#define RUMBLE_ADAPTER_END_OF(TYPE, FIELD) (offsetof(TYPE, FIELD) + sizeof(TYPE::FIELD))

/// The plugin's table read into the current shape: the bytes its minor has (and its struct_size
/// states), the entries appended since zero, i.e. null.
template <class Api>
Api current_table(const ComponentType& type) {
  const auto* plugin = static_cast<const Api*>(type.factory().api);
  const std::size_t n = std::min({static_cast<std::size_t>(plugin->struct_size),
                                  table_size(type.kind, type.abi_minor), sizeof(Api)});
  Api table{};
  std::memcpy(&table, plugin, n);
  table.struct_size = static_cast<std::uint32_t>(sizeof(Api));
  return table;
}

/// A 1.0 vehicle lists its output channels in one string, ';'-separated.
std::vector<std::string> split_names(const char* listed) {
  std::vector<std::string> names;
  const std::string all = listed != nullptr ? listed : "";
  std::size_t start = 0;
  while (start < all.size()) {
    const std::size_t end = all.find(';', start);
    names.push_back(all.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return names;
}

bool failed(rumble_status s) {
  return s != RUMBLE_OK && s != RUMBLE_WARNING;
}

}  // namespace

std::size_t table_size(rumble_kind kind, std::uint32_t abi_minor) {
  switch (kind) {
    case RUMBLE_KIND_VEHICLE:
      return abi_minor >= 1 ? RUMBLE_ADAPTER_END_OF(rumble_vehicle_api, outputs2)
                            : RUMBLE_ADAPTER_END_OF(rumble_vehicle_api, outputs);
    case RUMBLE_KIND_SOIL:
      return abi_minor >= 5   ? RUMBLE_ADAPTER_END_OF(rumble_soil_api, statics_done)
             : abi_minor >= 3 ? RUMBLE_ADAPTER_END_OF(rumble_soil_api, probe_resolution)
             : abi_minor >= 1 ? RUMBLE_ADAPTER_END_OF(rumble_soil_api, linear_matrix)
                              : RUMBLE_ADAPTER_END_OF(rumble_soil_api, receiver_velocity);
    case RUMBLE_KIND_COUPLER:
      return abi_minor >= 1 ? RUMBLE_ADAPTER_END_OF(rumble_coupler_api, lifecycle)
                            : RUMBLE_ADAPTER_END_OF(rumble_coupler_api, run);
  }
  return 0;
}

Capabilities capabilities_of(rumble_kind kind, const rumble_factory& f) {
  Capabilities c;
  const rumble_factory* factory = &f;
  const rumble_capabilities* declared =
      RUMBLE_HAS_FIELD(factory, rumble_factory, capabilities) ? f.capabilities : nullptr;
  if (declared != nullptr) {
    c.declared = true;
    c.offers = declared->offers;
    c.soil_needs = declared->soil_needs;
    c.max_macro_step = declared->max_macro_step;
    if (declared->participants_json != nullptr) c.participants_json = declared->participants_json;
    return c;
  }
  c.offers = RUMBLE_CAP_SAVE_RESTORE;
  if (kind == RUMBLE_KIND_SOIL) {
    const auto* soil = static_cast<const rumble_soil_api*>(f.api);
    if (soil->frequency_response != nullptr) c.offers |= RUMBLE_CAP_FREQUENCY_RESPONSE;
    if (soil->set_receivers != nullptr) c.offers |= RUMBLE_CAP_SURFACE_RECEIVERS;
  } else if (kind == RUMBLE_KIND_VEHICLE) {
    const auto* vehicle = static_cast<const rumble_vehicle_api*>(f.api);
    if (vehicle->tangent != nullptr) c.offers |= RUMBLE_CAP_TANGENT;
  }
  return c;
}

const rumble_lifecycle_api* lifecycle_of(const ComponentType& type) {
  if (type.abi_minor < 1) return nullptr;
  switch (type.kind) {
    case RUMBLE_KIND_VEHICLE:
      return static_cast<const rumble_vehicle_api*>(type.factory().api)->lifecycle;
    case RUMBLE_KIND_SOIL:
      return static_cast<const rumble_soil_api*>(type.factory().api)->lifecycle;
    case RUMBLE_KIND_COUPLER:
      return static_cast<const rumble_coupler_api*>(type.factory().api)->lifecycle;
  }
  return nullptr;
}

rumble_soil_api current_soil_table(const ComponentType& type) {
  return current_table<rumble_soil_api>(type);
}

rumble_coupler_api current_coupler_table(const ComponentType& type) {
  return current_table<rumble_coupler_api>(type);
}

// ---------------------------------------------------------------- vehicle

VehicleCalls::VehicleCalls(const ComponentType& type)
    : VehicleCalls(*static_cast<const rumble_vehicle_api*>(type.factory().api), type.abi_minor,
                   type.capabilities) {}

VehicleCalls::VehicleCalls(const rumble_vehicle_api& api, std::uint32_t abi_minor,
                           const Capabilities& caps)
    : api_(&api), lengths_(abi_minor >= 1) {
  tangent_ =
      lengths_ ? caps.has(RUMBLE_CAP_TANGENT) && api.tangent2 != nullptr : api.tangent != nullptr;
}

rumble_status VehicleCalls::dof_count(rumble_instance* self, std::uint64_t* n_dof) const {
  return api_->dof_count(self, n_dof);
}

rumble_status VehicleCalls::wheels(rumble_instance* self, rumble_wheel* out, std::uint64_t capacity,
                                   std::uint64_t* n_wheels) const {
  return api_->wheels(self, out, capacity, n_wheels);
}

rumble_status VehicleCalls::mass_matrix2(rumble_instance* self, const double* q,
                                         std::uint64_t n_dof, double* mass,
                                         std::uint64_t n_mass) const {
  if (lengths_) return api_->mass_matrix2(self, q, n_dof, mass, n_mass);
  return api_->mass_matrix(self, q, mass);
}

rumble_status VehicleCalls::forces2(rumble_instance* self, double t, const double* q,
                                    const double* qd, std::uint64_t n_dof, double* f) const {
  if (lengths_) return api_->forces2(self, t, q, qd, n_dof, f);
  return api_->forces(self, t, q, qd, f);
}

rumble_status VehicleCalls::wheel_kinematics2(rumble_instance* self, const double* q,
                                              std::uint64_t n_dof, double* z,
                                              std::uint64_t n_wheels, double* jacobian) const {
  if (lengths_) return api_->wheel_kinematics2(self, q, n_dof, z, n_wheels, jacobian);
  return api_->wheel_kinematics(self, q, z, jacobian);
}

rumble_status VehicleCalls::tangent2(rumble_instance* self, double t, const double* q,
                                     const double* qd, std::uint64_t n_dof, double* stiffness,
                                     double* damping) const {
  if (lengths_) return api_->tangent2(self, t, q, qd, n_dof, stiffness, damping);
  return api_->tangent(self, t, q, qd, stiffness, damping);
}

rumble_status VehicleCalls::output_names2(rumble_instance* self,
                                          std::vector<std::string>& names) const {
  names.clear();
  if (lengths_ && api_->output_names2 != nullptr) {  // abi.h: the 1.0 form when it is absent
    std::uint64_t n = 0;
    rumble_status s = api_->output_names2(self, nullptr, 0, &n);
    if (failed(s)) return s;
    std::vector<const char*> raw(static_cast<std::size_t>(n), nullptr);
    s = api_->output_names2(self, raw.data(), n, &n);
    for (const char* name : raw) names.emplace_back(name != nullptr ? name : "");
    return s;
  }
  if (api_->output_names != nullptr) names = split_names(api_->output_names(self));
  return RUMBLE_OK;
}

rumble_status VehicleCalls::outputs2(rumble_instance* self, double t, const double* q,
                                     const double* qd, std::uint64_t n_dof, double* values,
                                     std::uint64_t n_values) const {
  if (lengths_ && api_->outputs2 != nullptr)
    return api_->outputs2(self, t, q, qd, n_dof, values, n_values);
  if (api_->outputs != nullptr) return api_->outputs(self, t, q, qd, values);
  return RUMBLE_OK;
}

// ---------------------------------------------------------------- checkpoints

Checkpoints::Checkpoints(const rumble_common_api& common, const rumble_lifecycle_api* lifecycle,
                         const Capabilities& capabilities)
    : common_(&common),
      lifecycle_(lifecycle),
      plugin_held_(lifecycle != nullptr && lifecycle->checkpoint_save != nullptr &&
                   capabilities.has(RUMBLE_CAP_OWN_CHECKPOINTS)) {}

rumble_status Checkpoints::state_size(rumble_instance* self, std::uint64_t* n) const {
  return common_->state_size(self, n);
}

rumble_status Checkpoints::save(rumble_instance* self, std::uint32_t slot) {
  if (plugin_held_) return lifecycle_->checkpoint_save(self, slot);
  std::vector<double>& buffer = slots_.at(slot);
  if (buffer.empty()) {  // sized once: no allocation after the first save
    std::uint64_t n = 0;
    const rumble_status s = common_->state_size(self, &n);
    if (failed(s)) return s;
    buffer.resize(static_cast<std::size_t>(n));
  }
  const rumble_status s = common_->save_state(self, buffer.data(), buffer.size());
  saved_.at(slot) = !failed(s);
  return s;
}

rumble_status Checkpoints::restore(rumble_instance* self, std::uint32_t slot) const {
  if (plugin_held_) return lifecycle_->checkpoint_restore(self, slot);
  const std::vector<double>& buffer = slots_.at(slot);
  return common_->restore_state(self, buffer.data(), buffer.size());
}

rumble_status Checkpoints::release(rumble_instance* self, std::uint32_t slot) {
  if (plugin_held_) {
    return lifecycle_->checkpoint_free != nullptr ? lifecycle_->checkpoint_free(self, slot)
                                                  : RUMBLE_OK;
  }
  std::vector<double>().swap(slots_.at(slot));
  saved_.at(slot) = false;
  return RUMBLE_OK;
}

// ---------------------------------------------------------------- couplers

bool coupler_takes_discard(std::uint32_t abi_minor) {
  return abi_minor >= 1;
}

std::string step_report_defect(const rumble_step_report* report) {
  if (!RUMBLE_HAS_FIELD(report, rumble_step_report, participants))
    return "coupler's step report is shorter than ABI 1.1's";
  if (report->n_residuals > 0 && report->residuals == nullptr)
    return "coupler's step report has residuals but no array";
  return "";
}

}  // namespace rumble::abi
