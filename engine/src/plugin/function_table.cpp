#include "plugin/function_table.hpp"

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

/// The table's own struct_size against the ABI 1.0 size of its kind (this host's sizeof: no
/// field has been appended since 1.0).
std::string size_defect(std::uint32_t size, std::size_t needed) {
  if (size >= needed) return "";
  return "function table struct_size " + std::to_string(size) + " bytes, ABI 1.0 needs " +
         std::to_string(needed);
}

}  // namespace

std::string function_table_defect(rumble_kind kind, const void* api) {
  switch (kind) {
    case RUMBLE_KIND_VEHICLE: {
      const auto& t = *static_cast<const rumble_vehicle_api*>(api);
      std::string d = size_defect(t.struct_size, sizeof(rumble_vehicle_api));
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
      return d;
    }
    case RUMBLE_KIND_SOIL: {
      const auto& t = *static_cast<const rumble_soil_api*>(api);
      std::string d = size_defect(t.struct_size, sizeof(rumble_soil_api));
      if (d.empty()) d = common_missing(t.common);
      if (d.empty()) {
        d = first_missing({{"accept_layout", t.accept_layout != nullptr},
                           {"initialize", t.initialize != nullptr},
                           {"advance", t.advance != nullptr},
                           {"motion", t.motion != nullptr}});
      }
      if (d.empty() && (t.set_receivers == nullptr) != (t.receiver_velocity == nullptr))
        d = "function table has only one of 'set_receivers' and 'receiver_velocity'";
      return d;
    }
    case RUMBLE_KIND_COUPLER: {
      const auto& t = *static_cast<const rumble_coupler_api*>(api);
      std::string d = size_defect(t.struct_size, sizeof(rumble_coupler_api));
      if (d.empty()) d = common_missing(t.common);
      if (d.empty()) d = first_missing({{"run", t.run != nullptr}});
      return d;
    }
  }
  return "unknown kind";
}

}  // namespace rumble
