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

#include <array>
#include <rumble/plugin/component.hpp>
#include <rumble/plugin/coupler.hpp>
#include <rumble/plugin/detail_common.hpp>
#include <rumble/plugin/detail_soil_api.hpp>
#include <rumble/plugin/detail_vehicle_api.hpp>
#include <rumble/plugin/soil.hpp>
#include <rumble/plugin/vehicle.hpp>
#include <type_traits>

namespace rumble {
namespace detail {

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
