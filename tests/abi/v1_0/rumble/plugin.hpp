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
// RUMBLE_DISCARD (state unchanged, caller may retry), anything else RUMBLE_ERROR, with what()
// as the message. The host validates params against the schema (and fills declared defaults)
// before the constructor runs. C++17, standard library only.
#ifndef RUMBLE_PLUGIN_HPP
#define RUMBLE_PLUGIN_HPP

#include <rumble/abi.h>

#include <array>
#include <complex>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace rumble {

/// Thrown by plugin code to refuse a step without changing state (maps to RUMBLE_DISCARD).
class Discard : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Host services (logging, scenario directory). Cheap to copy; valid for the instance's life.
class Host {
 public:
  explicit Host(const rumble_host* host) : host_(host) {}
  void log(rumble_log_level level, const std::string& message) const {
    if (host_ != nullptr && host_->log != nullptr)
      host_->log(host_->host_data, level, message.c_str());
  }
  void debug(const std::string& m) const { log(RUMBLE_LOG_DEBUG, m); }
  void info(const std::string& m) const { log(RUMBLE_LOG_INFO, m); }
  void warn(const std::string& m) const { log(RUMBLE_LOG_WARN, m); }
  std::string scenario_dir() const {
    return host_ != nullptr && host_->scenario_dir != nullptr ? host_->scenario_dir : ".";
  }

 private:
  const rumble_host* host_;
};

/// What every component may offer: full-state save/restore as a flat vector of doubles.
class Component {
 public:
  virtual ~Component() = default;
  /// Number of doubles of the full state; 0 means save/restore is not supported.
  virtual std::size_t state_size() const { return 0; }
  virtual void save_state(double* /*buffer*/) const {}
  virtual void restore_state(const double* /*buffer*/) {}

  /// Call from any method to make it return RUMBLE_WARNING with this text (result still valid).
  void warn_caller(std::string message) { pending_warning_ = std::move(message); }
  /// Used by the boundary wrappers only.
  std::string take_warning() { return std::exchange(pending_warning_, std::string()); }

 private:
  std::string pending_warning_;
};

/// A wheel of a vehicle, in the vehicle frame.
using Wheel = rumble_wheel;

/// Model-exchange vehicle: see rumble_vehicle_api in abi.h for the equations and signs.
class Vehicle : public Component {
 public:
  static constexpr rumble_kind kKind = RUMBLE_KIND_VEHICLE;
  virtual std::size_t dof_count() const = 0;
  virtual std::vector<Wheel> wheels() const = 0;
  /// mass: dof x dof, column-major.
  virtual void mass_matrix(const double* q, double* mass) = 0;
  /// Generalized forces except contact; gravity acts in +z (downward).
  virtual void forces(double t, const double* q, const double* qd, double* f) = 0;
  /// z: n_wheels positions [m] (down +, 0 at the nominal height); jacobian: n_wheels x dof.
  virtual void wheel_kinematics(const double* q, double* z, double* jacobian) = 0;
  /// Return true and fill K = -df/dq, C = -df/dq' when known analytically.
  virtual bool tangent(double /*t*/, const double* /*q*/, const double* /*qd*/,
                       double* /*stiffness*/, double* /*damping*/) {
    return false;
  }
  /// Optional output channels ("name [unit]"), written by outputs().
  virtual std::vector<std::string> output_names() const { return {}; }
  virtual void outputs(double /*t*/, const double* /*q*/, const double* /*qd*/,
                       double* /*values*/) {}
};

using Footprint = rumble_footprint;
using Receiver = rumble_receiver;

/// A force waveform over one macro step (see rumble_waveform).
class Waveform {
 public:
  explicit Waveform(const rumble_waveform& w) : w_(w) {}
  std::size_t channels() const { return static_cast<std::size_t>(w_.n); }
  /// Value of channel i at tau = (t - t_step) / H in [0, 1].
  double at(std::size_t i, double tau) const {
    double value = 0.0;
    for (int k = static_cast<int>(w_.order); k >= 0; --k)
      value = value * tau + w_.coeff[static_cast<std::size_t>(k) * w_.n + i];
    return value;
  }

 private:
  rumble_waveform w_;
};

/// Soil participant: see rumble_soil_api in abi.h.
class Soil : public Component {
 public:
  static constexpr rumble_kind kKind = RUMBLE_KIND_SOIL;
  virtual void accept_layout(const std::vector<Footprint>& footprints) = 0;
  virtual void initialize(double t0, const double* static_force, double* static_u) = 0;
  virtual void advance(double t, double H, const Waveform& force) = 0;
  virtual void motion(double* u, double* v) const = 0;
  /// Return false when not offered; else fill receptance [m/N], n x n column-major.
  virtual bool frequency_response(double /*f_hz*/, std::complex<double>* /*receptance*/) {
    return false;
  }
  /// Return false when receivers are not offered.
  virtual bool set_receivers(const std::vector<Receiver>& /*receivers*/) { return false; }
  virtual void receiver_velocity(double* /*v*/) const {}
};

/// The host's participant interface as seen by a coupler; errors become exceptions.
class CosimHost {
 public:
  /// Thrown when the host asks the coupler to stop (Ctrl-C, plugin error): status preserved.
  class Stop : public std::runtime_error {
   public:
    Stop(rumble_status s, const std::string& what) : std::runtime_error(what), status(s) {}
    rumble_status status;
  };
  static constexpr std::uint32_t kTrack = RUMBLE_PARTICIPANT_TRACK;
  static constexpr std::uint32_t kSoil = RUMBLE_PARTICIPANT_SOIL;

  explicit CosimHost(const rumble_cosim_host* h) : h_(h) {}
  std::size_t interface_size() const {
    return static_cast<std::size_t>(h_->interface_size(h_->ctx));
  }
  std::size_t output_size(std::uint32_t p) const {
    return static_cast<std::size_t>(h_->output_size(h_->ctx, p));
  }
  void get_output(std::uint32_t p, std::vector<double>& y) const {
    check(h_->get_output(h_->ctx, p, y.data(), y.size()), "get_output");
  }
  /// coeff: (order + 1) * channels values, see rumble_waveform.
  void set_input(std::uint32_t p, std::uint32_t order, const std::vector<double>& coeff) const {
    const rumble_waveform w{order, coeff.size() / (order + 1u), coeff.data()};
    check(h_->set_input(h_->ctx, p, &w), "set_input");
  }
  /// Returns the status (OK, WARNING or DISCARD); ERROR/FATAL throw Stop.
  rumble_status advance(std::uint32_t p, double t, double H) const {
    return check(h_->advance(h_->ctx, p, t, H), "advance");
  }
  void save(std::uint32_t p, std::uint32_t slot) const {
    check(h_->save(h_->ctx, p, slot), "save");
  }
  void restore(std::uint32_t p, std::uint32_t slot) const {
    check(h_->restore(h_->ctx, p, slot), "restore");
  }
  void step_done(double t, double H, double residual) const {
    check(h_->step_done(h_->ctx, t, H, residual), "step_done");
  }
  void log(rumble_log_level level, const std::string& m) const {
    h_->log(h_->ctx, level, m.c_str());
  }

 private:
  rumble_status check(rumble_status s, const char* what) const {
    if (s == RUMBLE_ERROR || s == RUMBLE_FATAL)
      throw Stop(s, std::string("host ") + what + " stopped the run");
    return s;
  }
  const rumble_cosim_host* h_;
};

/// Coupling scheme: the master algorithm over macro steps.
class Coupler : public Component {
 public:
  static constexpr rumble_kind kKind = RUMBLE_KIND_COUPLER;
  virtual void run(const CosimHost& host, double t0, double t_end, double H) = 0;
};

namespace detail {

struct Box {
  std::unique_ptr<Component> object;
  std::string message;
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
    });
  };
  return c;
}

template <class T>
const rumble_vehicle_api* vehicle_api() {
  static const rumble_vehicle_api api = [] {
    rumble_vehicle_api a{};
    a.struct_size = sizeof(rumble_vehicle_api);
    a.common = common_api();
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
    a.tangent = [](rumble_instance* s, double t, const double* q, const double* qd, double* k,
                   double* c) {
      bool known = false;
      const rumble_status st = guard(s, [&] { known = object<T>(s).tangent(t, q, qd, k, c); });
      if (st == RUMBLE_OK && !known) {
        box(s)->message = "no analytical tangent";
        return RUMBLE_DISCARD;
      }
      return st;
    };
    a.output_names = [](rumble_instance* s) -> const char* {
      Box* b = box(s);
      b->message.clear();
      for (const std::string& n : object<T>(s).output_names())
        b->message += (b->message.empty() ? "" : ";") + n;
      return b->message.c_str();
    };
    a.outputs = [](rumble_instance* s, double t, const double* q, const double* qd, double* v) {
      return guard(s, [&] { object<T>(s).outputs(t, q, qd, v); });
    };
    return a;
  }();
  return &api;
}

template <class T>
const rumble_soil_api* soil_api() {
  static const rumble_soil_api api = [] {
    rumble_soil_api a{};
    a.struct_size = sizeof(rumble_soil_api);
    a.common = common_api();
    a.accept_layout = [](rumble_instance* s, const rumble_footprint* fp, std::uint64_t n) {
      return guard(s, [&] { object<T>(s).accept_layout(std::vector<Footprint>(fp, fp + n)); });
    };
    a.initialize = [](rumble_instance* s, double t0, const double* f, double* u, std::uint64_t) {
      return guard(s, [&] { object<T>(s).initialize(t0, f, u); });
    };
    a.advance = [](rumble_instance* s, double t, double H, const rumble_waveform* w) {
      return guard(s, [&] { object<T>(s).advance(t, H, Waveform(*w)); });
    };
    a.motion = [](rumble_instance* s, double* u, double* v, std::uint64_t) {
      return guard(s, [&] { object<T>(s).motion(u, v); });
    };
    a.frequency_response = [](rumble_instance* s, double f, double* re, double* im,
                              std::uint64_t n) {
      bool offered = false;
      const rumble_status st = guard(s, [&] {
        std::vector<std::complex<double>> h(static_cast<std::size_t>(n * n));
        offered = object<T>(s).frequency_response(f, h.data());
        for (std::size_t k = 0; offered && k < h.size(); ++k) {
          re[k] = h[k].real();
          im[k] = h[k].imag();
        }
      });
      if (st == RUMBLE_OK && !offered) {
        box(s)->message = "frequency response not offered";
        return RUMBLE_DISCARD;
      }
      return st;
    };
    a.set_receivers = [](rumble_instance* s, const rumble_receiver* r, std::uint64_t n) {
      bool offered = false;
      const rumble_status st =
          guard(s, [&] { offered = object<T>(s).set_receivers(std::vector<Receiver>(r, r + n)); });
      if (st == RUMBLE_OK && !offered) {
        box(s)->message = "receivers not offered";
        return RUMBLE_DISCARD;
      }
      return st;
    };
    a.receiver_velocity = [](rumble_instance* s, double* v, std::uint64_t) {
      return guard(s, [&] { object<T>(s).receiver_velocity(v); });
    };
    return a;
  }();
  return &api;
}

template <class T>
const rumble_coupler_api* coupler_api() {
  static const rumble_coupler_api api = [] {
    rumble_coupler_api a{};
    a.struct_size = sizeof(rumble_coupler_api);
    a.common = common_api();
    a.run = [](rumble_instance* s, const rumble_cosim_host* h, double t0, double t1, double H) {
      return guard(s, [&] { object<T>(s).run(CosimHost(h), t0, t1, H); });
    };
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
    b->object = std::make_unique<T>(std::string(params != nullptr ? params : "{}"), Host(host));
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
  if constexpr (std::is_base_of_v<Vehicle, T>) f.api = vehicle_api<T>();
  if constexpr (std::is_base_of_v<Soil, T>) f.api = soil_api<T>();
  if constexpr (std::is_base_of_v<Coupler, T>) f.api = coupler_api<T>();
  return f;
}

#define RUMBLE_DETAIL_STR2(x) #x
#define RUMBLE_DETAIL_STR(x) RUMBLE_DETAIL_STR2(x)

template <class... Ts>
const rumble_plugin_descriptor* descriptor(const char* name, const char* version) {
  static const std::array<rumble_factory, sizeof...(Ts)> factories{factory<Ts>()...};
  static const rumble_plugin_descriptor d{sizeof(rumble_plugin_descriptor),
                                          RUMBLE_ABI_MAJOR,
                                          RUMBLE_ABI_MINOR,
                                          name,
                                          version,
                                          "g++/clang " __VERSION__
                                          ", C++ " RUMBLE_DETAIL_STR(__cplusplus),
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
