// template_vehicle_test: the built template_vehicle library, loaded the way the engine loads it
// (dlopen, the one exported entry point, the C function table), against the closed form of its
// equation m q'' = m g + P - F. Standard C++17 and the SDK headers only: no test framework, no
// engine. `ctest` runs it with the library's path as the argument; it prints each failed check
// and exits non-zero when there is one.
#include <dlfcn.h>
#include <rumble/abi.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

namespace {

constexpr const char* kType = "template_vehicle";
constexpr double kMass = 750.0;     // kg
constexpr double kPreload = 5.0e4;  // N
constexpr double kGravity = 9.81;   // m/s^2

int failures = 0;

void check(bool ok, const std::string& what) {
  if (!ok) {
    ++failures;
    std::fprintf(stderr, "FAILED: %s\n", what.c_str());
  }
}

void check_close(double actual, double expected, double relative, const std::string& what) {
  check(std::abs(actual - expected) <= relative * std::abs(expected),
        what + ": " + std::to_string(actual) + " instead of " + std::to_string(expected));
}

/// The factory of `type` in the library at `path`, or null with the reason printed. The library
/// stays loaded for the rest of the process, as the engine keeps it.
const rumble_factory* load_factory(const char* path, int kind, const char* type) {
  void* library = dlopen(path, RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr) {
    std::fprintf(stderr, "cannot load %s: %s\n", path, dlerror());
    return nullptr;
  }
  void* symbol = dlsym(library, RUMBLE_PLUGIN_ENTRY_SYMBOL);
  if (symbol == nullptr) {
    std::fprintf(stderr, "%s exports no %s\n", path, RUMBLE_PLUGIN_ENTRY_SYMBOL);
    return nullptr;
  }
  rumble_plugin_entry_fn entry = nullptr;
  std::memcpy(&entry, &symbol, sizeof entry);  // object to function pointer, as dlsym needs
  const rumble_plugin_descriptor* d = entry();
  for (std::uint64_t i = 0; i < d->n_factories; ++i) {
    const rumble_factory& f = d->factories[i];
    if (f.kind == kind && std::strcmp(f.type_name, type) == 0) return &f;
  }
  std::fprintf(stderr, "%s provides no type '%s' of kind %d\n", path, type, kind);
  return nullptr;
}

/// The vertical acceleration q'' = (f - J F) / m the plugin's equations give at (t, q, q') under
/// a contact force F, for a one-DOF, one-wheel vehicle.
double acceleration(const rumble_vehicle_api& api, rumble_instance* self, double t, double q,
                    double qd, double contact_force) {
  double m = 0.0, f = 0.0, z = 0.0, j = 0.0;
  check(api.mass_matrix2(self, &q, 1, &m, 1) == RUMBLE_OK, "mass_matrix");
  check(api.forces2(self, t, &q, &qd, 1, &f) == RUMBLE_OK, "forces");
  check(api.wheel_kinematics2(self, &q, 1, &z, 1, &j) == RUMBLE_OK, "wheel_kinematics");
  check(z == q && j == 1.0, "the wheel moves with the mass: z = q, J = 1");
  return (f - j * contact_force) / m;
}

void equations(const rumble_factory& f) {
  rumble_host host{};
  host.struct_size = sizeof(rumble_host);
  host.abi_minor = RUMBLE_ABI_MINOR;
  const std::string params =
      "{\"mass\": " + std::to_string(kMass) + ", \"preload\": " + std::to_string(kPreload) + "}";
  rumble_instance* self = nullptr;
  const char* error = nullptr;
  if (f.create(params.c_str(), &host, &self, &error) != RUMBLE_OK) {
    check(false, std::string("create: ") + (error != nullptr ? error : ""));
    return;
  }
  const auto& api = *static_cast<const rumble_vehicle_api*>(f.api);

  std::uint64_t n = 0;
  check(api.dof_count(self, &n) == RUMBLE_OK && n == 1, "one DOF");
  rumble_wheel wheels[2] = {};
  check(api.wheels(self, wheels, 2, &n) == RUMBLE_OK && n == 1, "one wheel");
  check(wheels[0].offset == 0.0 && wheels[0].radius == 0.46, "wheel at 0 m, default radius");

  // At any state (the engine evaluates trial states): at rest under the static wheel load
  // m g + P, in free fall at g + P / m when the wheel carries nothing.
  for (const double q : {0.0, 1e-3, -2e-3}) {
    for (const double qd : {0.0, 0.05}) {
      const std::string at = " at q = " + std::to_string(q) + ", q' = " + std::to_string(qd);
      const double a_static = acceleration(api, self, 0.3, q, qd, kMass * kGravity + kPreload);
      check(std::abs(a_static) <= 1e-12 * kGravity, "at rest under m g + P" + at);
      check_close(acceleration(api, self, 0.3, q, qd, 0.0), kGravity + kPreload / kMass, 1e-14,
                  "free fall" + at);
    }
  }

  // The analytical tangent agrees with central differences of forces() (both zero here).
  double k = 1.0, c = 1.0, f_plus = 0.0, f_minus = 0.0;
  const double q = 1e-3, qd = 0.0, dq = 1e-6, q_plus = q + dq, q_minus = q - dq;
  check(api.tangent2(self, 0.0, &q, &qd, 1, &k, &c) == RUMBLE_OK, "tangent offered");
  check(api.forces2(self, 0.0, &q_plus, &qd, 1, &f_plus) == RUMBLE_OK, "forces(q + dq)");
  check(api.forces2(self, 0.0, &q_minus, &qd, 1, &f_minus) == RUMBLE_OK, "forces(q - dq)");
  check(std::abs(k + (f_plus - f_minus) / (2 * dq)) <= 1e-6, "K = -df/dq");
  check(c == 0.0, "C = 0");
  api.common.destroy(self);
}

// A mass the schema would let through only by mistake is refused with what, the value, the fix.
void refuses_zero_mass(const rumble_factory& f) {
  rumble_host host{};
  host.struct_size = sizeof(rumble_host);
  rumble_instance* self = nullptr;
  const char* error = nullptr;
  check(f.create("{\"mass\": 0}", &host, &self, &error) == RUMBLE_ERROR, "create with mass 0");
  const std::string message = error != nullptr ? error : "";
  check(message == "params/mass: 0.000000 kg; must be > 0 (the wheel needs inertia)",
        "message: " + message);
  if (self != nullptr) static_cast<const rumble_vehicle_api*>(f.api)->common.destroy(self);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s <path of %s.so>\n", argv[0], kType);
    return 2;
  }
  const rumble_factory* f = load_factory(argv[1], RUMBLE_KIND_VEHICLE, kType);
  if (f == nullptr) return 1;
  equations(*f);
  refuses_zero_mass(*f);
  if (failures == 0) std::printf("%s: all checks passed\n", kType);
  return failures == 0 ? 0 : 1;
}
