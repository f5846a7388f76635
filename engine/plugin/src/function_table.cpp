#include "plugin/function_table.hpp"

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "plugin/abi_adapter.hpp"

namespace rumble {
namespace {

using RequiredFunction = std::pair<const char*, bool>;  // name, present

std::string first_missing(std::initializer_list<RequiredFunction> required) {
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

/// "" when a factory's declared capabilities are well formed, else what is wrong.
std::string capabilities_defect(const rumble_factory* f) {
  if (!RUMBLE_HAS_FIELD(f, rumble_factory, capabilities) || f->capabilities == nullptr) return "";
  const rumble_capabilities& c = *f->capabilities;
  constexpr std::size_t kCapabilitiesV1_1 = RUMBLE_END_OF(rumble_capabilities, participants_json);
  if (c.struct_size < kCapabilitiesV1_1) {
    return "capabilities struct_size " + std::to_string(c.struct_size) + " bytes, ABI 1.1 needs " +
           std::to_string(kCapabilitiesV1_1);
  }
  if (!(c.max_macro_step >= 0.0)) return "capabilities max_macro_step is negative or NaN";
  if ((c.offers & RUMBLE_CAP_MONOLITHIC) != 0) {
    if (f->kind != RUMBLE_KIND_COUPLER) return "capability MONOLITHIC is for couplers only";
    if ((c.soil_needs & RUMBLE_CAP_LINEAR_MATRICES) == 0)
      return "a MONOLITHIC coupler must need LINEAR_MATRICES of its soil (soil_needs)";
  }
  if ((c.offers & RUMBLE_CAP_DISTRIBUTED) != 0 && f->kind != RUMBLE_KIND_SOIL)
    return "capability DISTRIBUTED is for soils only (the host mirrors a soil's calls to every "
           "rank; docs/decisions/0012-distributed-soil.md)";
  if ((c.offers & RUMBLE_CAP_NEVER_REFUSES) != 0 && f->kind == RUMBLE_KIND_COUPLER)
    return "capability NEVER_REFUSES is for vehicles and soils, whose advance could refuse";
  if (c.participants_json != nullptr) {
    const auto j = nlohmann::json::parse(c.participants_json, nullptr, false);
    if (!j.is_object()) return "capabilities participants_json is not a JSON object";
  }
  return "";
}

}  // namespace

std::string factory_capabilities_defect(const rumble_factory& f, std::uint32_t abi_minor) {
  constexpr std::size_t kFactoryV1_1 = RUMBLE_END_OF(rumble_factory, capabilities);
  if (abi_minor >= 1 && f.struct_size < kFactoryV1_1)
    return "struct_size " + std::to_string(f.struct_size) + " bytes, ABI 1.1 needs " +
           std::to_string(kFactoryV1_1);
  std::string defect = capabilities_defect(&f);
  if (defect.empty() && abi_minor >= 1 && f.capabilities != nullptr &&
      (f.kind == RUMBLE_KIND_VEHICLE || f.kind == RUMBLE_KIND_SOIL ||
       f.kind == RUMBLE_KIND_COUPLER))
    defect =
        declared_functions_defect(static_cast<rumble_kind>(f.kind), f.api, f.capabilities->offers);
  return defect;
}

std::string function_table_defect(rumble_kind kind, const void* api, std::uint32_t abi_minor) {
  const bool v1_1 = abi_minor >= 1;
  switch (kind) {
    case RUMBLE_KIND_VEHICLE: {
      const auto& t = *static_cast<const rumble_vehicle_api*>(api);
      std::string d = size_defect(t.struct_size, abi::table_size(kind, abi_minor), abi_minor);
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
      if (d.empty() && v1_1) {  // the 1.1 host calls these instead of their 1.0 forms
        d = first_missing({{"mass_matrix2", t.mass_matrix2 != nullptr},
                           {"forces2", t.forces2 != nullptr},
                           {"wheel_kinematics2", t.wheel_kinematics2 != nullptr}});
      }
      if (d.empty() && v1_1 && (t.output_names2 == nullptr) != (t.outputs2 == nullptr))
        d = "function table has only one of 'output_names2' and 'outputs2'";
      if (d.empty() && v1_1) d = lifecycle_defect(t.lifecycle);
      return d;
    }
    case RUMBLE_KIND_SOIL: {
      const auto& t = *static_cast<const rumble_soil_api*>(api);
      std::string d = size_defect(t.struct_size, abi::table_size(kind, abi_minor), abi_minor);
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
      std::string d = size_defect(t.struct_size, abi::table_size(kind, abi_minor), abi_minor);
      if (d.empty()) d = common_missing(t.common);
      if (d.empty()) d = first_missing({{"run", t.run != nullptr}});
      if (d.empty() && v1_1) d = lifecycle_defect(t.lifecycle);
      return d;
    }
  }
  return "unknown kind";
}

std::string declared_functions_defect(rumble_kind kind, const void* api, std::uint64_t offers) {
  struct Need {
    std::uint64_t bit;
    const char* capability;
    const char* function;
    bool present;
  };
  std::vector<Need> needs;
  const rumble_lifecycle_api* lifecycle = nullptr;
  if (kind == RUMBLE_KIND_SOIL) {
    const auto& t = *static_cast<const rumble_soil_api*>(api);
    lifecycle = t.lifecycle;
    needs = {{RUMBLE_CAP_RECEIVERS, "receivers", "set_probes", t.set_probes != nullptr},
             {RUMBLE_CAP_RECEIVERS, "receivers", "probe_samples", t.probe_samples != nullptr},
             {RUMBLE_CAP_SURFACE_RECEIVERS, "surface_receivers", "set_receivers",
              t.set_receivers != nullptr},
             {RUMBLE_CAP_FREQUENCY_RESPONSE, "frequency_response", "frequency_response",
              t.frequency_response != nullptr},
             {RUMBLE_CAP_FIELD_OUTPUT, "field_output", "write_fields", t.write_fields != nullptr},
             {RUMBLE_CAP_WAVE_SPEEDS, "wave_speeds", "wave_speeds", t.wave_speeds != nullptr},
             {RUMBLE_CAP_LINEAR_MATRICES, "linear_matrices", "linear_matrix",
              t.linear_matrix != nullptr}};
  } else if (kind == RUMBLE_KIND_VEHICLE) {
    const auto& t = *static_cast<const rumble_vehicle_api*>(api);
    lifecycle = t.lifecycle;
    needs = {{RUMBLE_CAP_TANGENT, "tangent", "tangent2", t.tangent2 != nullptr}};
  } else if (kind == RUMBLE_KIND_COUPLER) {
    lifecycle = static_cast<const rumble_coupler_api*>(api)->lifecycle;
  }
  const bool own = lifecycle != nullptr && lifecycle->checkpoint_save != nullptr &&
                   lifecycle->checkpoint_restore != nullptr;
  needs.push_back(
      {RUMBLE_CAP_OWN_CHECKPOINTS, "own_checkpoints", "lifecycle checkpoint_save", own});
  for (const Need& n : needs) {
    if ((offers & n.bit) != 0 && !n.present)
      return std::string("declares ") + n.capability + " but its function table has no '" +
             n.function + "'";
  }
  return "";
}

}  // namespace rumble
