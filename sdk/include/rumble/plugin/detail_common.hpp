// SPDX-License-Identifier: MIT
// rumble/plugin/detail_common.hpp (internal to rumble/plugin.hpp): the box behind every C handle,
// the exception guard, and the capabilities and common functions derived from a class.
#ifndef RUMBLE_PLUGIN_DETAIL_COMMON_HPP
#define RUMBLE_PLUGIN_DETAIL_COMMON_HPP

#include <rumble/abi.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <rumble/plugin/component.hpp>
#include <rumble/plugin/coupler.hpp>
#include <rumble/plugin/soil.hpp>
#include <rumble/plugin/vehicle.hpp>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace rumble {
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

}  // namespace detail
}  // namespace rumble

#endif  // RUMBLE_PLUGIN_DETAIL_COMMON_HPP
