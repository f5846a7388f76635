// SPDX-License-Identifier: MIT
// rumble/plugin/detail_vehicle_api.hpp (internal to rumble/plugin.hpp): a Vehicle class's C table.
#ifndef RUMBLE_PLUGIN_DETAIL_VEHICLE_API_HPP
#define RUMBLE_PLUGIN_DETAIL_VEHICLE_API_HPP

#include <rumble/plugin/detail_common.hpp>

namespace rumble {
namespace detail {

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

}  // namespace detail
}  // namespace rumble

#endif  // RUMBLE_PLUGIN_DETAIL_VEHICLE_API_HPP
