#include "plugin/function_table.hpp"

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <utility>

namespace rumble {
namespace {

using Entry = std::pair<const char*, bool>;  // name, present

std::string first_missing(std::initializer_list<Entry> required) {
  for (const auto& [name, present] : required) {
    if (!present) return std::string("function table has no '") + name + "'";
  }
  return "";
}

std::string common_missing(const rumble_common_api& c) {
  return first_missing({{"destroy", c.destroy != nullptr},
                        {"last_message", c.last_message != nullptr},
                        {"state_size", c.state_size != nullptr},
                        {"save_state", c.save_state != nullptr},
                        {"restore_state", c.restore_state != nullptr}});
}

/// End of FIELD in TYPE: the size a table must have to hold it.
#define RUMBLE_END_OF(TYPE, FIELD) (offsetof(TYPE, FIELD) + sizeof(TYPE::FIELD))

/// The table's own struct_size against the size of the ABI minor the plugin was built for.
std::string size_defect(std::uint32_t size, std::size_t needed, std::uint32_t abi_minor) {
  if (size >= needed) return "";
  return "function table struct_size " + std::to_string(size) + " bytes, ABI 1." +
         std::to_string(abi_minor) + " needs " + std::to_string(needed);
}

/// A lifecycle table (1.1), when present, must be at least its 1.1 size.
std::string lifecycle_defect(const rumble_lifecycle_api* l) {
  if (l == nullptr) return "";
  const std::size_t needed = RUMBLE_END_OF(rumble_lifecycle_api, checkpoint_free);
  if (l->struct_size < needed) {
    return "lifecycle table struct_size " + std::to_string(l->struct_size) +
           " bytes, ABI 1.1 needs " + std::to_string(needed);
  }
  if ((l->checkpoint_save == nullptr) != (l->checkpoint_restore == nullptr))
    return "lifecycle table has only one of 'checkpoint_save' and 'checkpoint_restore'";
  return "";
}

}  // namespace

std::string function_table_defect(rumble_kind kind, const void* api, std::uint32_t abi_minor) {
  const bool v1_1 = abi_minor >= 1;
  switch (kind) {
    case RUMBLE_KIND_VEHICLE: {
      const auto& t = *static_cast<const rumble_vehicle_api*>(api);
      std::string d = size_defect(t.struct_size,
                                  v1_1 ? RUMBLE_END_OF(rumble_vehicle_api, outputs2)
                                       : RUMBLE_END_OF(rumble_vehicle_api, outputs),
                                  abi_minor);
      if (d.empty()) d = common_missing(t.common);
      if (d.empty()) {
        d = first_missing({{"dof_count", t.dof_count != nullptr},
                           {"wheels", t.wheels != nullptr},
                           {"mass_matrix", t.mass_matrix != nullptr},
                           {"forces", t.forces != nullptr},
                           {"wheel_kinematics", t.wheel_kinematics != nullptr}});
      }
      if (d.empty() && t.output_names != nullptr && t.outputs == nullptr)
        d = "function table has 'output_names' but no 'outputs'";
      if (d.empty() && v1_1) d = lifecycle_defect(t.lifecycle);
      return d;
    }
    case RUMBLE_KIND_SOIL: {
      const auto& t = *static_cast<const rumble_soil_api*>(api);
      std::string d = size_defect(t.struct_size,
                                  v1_1 ? RUMBLE_END_OF(rumble_soil_api, linear_matrix)
                                       : RUMBLE_END_OF(rumble_soil_api, receiver_velocity),
                                  abi_minor);
      if (d.empty()) d = common_missing(t.common);
      if (d.empty()) {
        d = first_missing({{"accept_layout", t.accept_layout != nullptr},
                           {"initialize", t.initialize != nullptr},
                           {"advance", t.advance != nullptr},
                           {"motion", t.motion != nullptr}});
      }
      if (d.empty() && (t.set_receivers == nullptr) != (t.receiver_velocity == nullptr))
        d = "function table has only one of 'set_receivers' and 'receiver_velocity'";
      if (d.empty() && v1_1 && (t.set_probes == nullptr) != (t.probe_samples == nullptr))
        d = "function table has only one of 'set_probes' and 'probe_samples'";
      if (d.empty() && v1_1) d = lifecycle_defect(t.lifecycle);
      return d;
    }
    case RUMBLE_KIND_COUPLER: {
      const auto& t = *static_cast<const rumble_coupler_api*>(api);
      std::string d = size_defect(t.struct_size,
                                  v1_1 ? RUMBLE_END_OF(rumble_coupler_api, lifecycle)
                                       : RUMBLE_END_OF(rumble_coupler_api, run),
                                  abi_minor);
      if (d.empty()) d = common_missing(t.common);
      if (d.empty()) d = first_missing({{"run", t.run != nullptr}});
      if (d.empty() && v1_1) d = lifecycle_defect(t.lifecycle);
      return d;
    }
  }
  return "unknown kind";
}

}  // namespace rumble
