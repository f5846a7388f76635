// SPDX-License-Identifier: MIT
// rumble/plugin/detail_soil_api.hpp (internal to rumble/plugin.hpp): a Soil class's C table.
#ifndef RUMBLE_PLUGIN_DETAIL_SOIL_API_HPP
#define RUMBLE_PLUGIN_DETAIL_SOIL_API_HPP

#include <rumble/plugin/detail_common.hpp>

namespace rumble {
namespace detail {

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
  a.size = [](rumble_instance* s, std::uint64_t* n_dof, double* peak_bytes) {
    return guard(s, [&] {
      const Soil::Size size = object<T>(s).size();
      *n_dof = size.dofs;
      *peak_bytes = size.peak_bytes;
    });
  };
  a.statics_done = [](rumble_instance* s) {
    return guard(s, [&] { object<T>(s).statics_done(); });
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

}  // namespace detail
}  // namespace rumble

#endif  // RUMBLE_PLUGIN_DETAIL_SOIL_API_HPP
