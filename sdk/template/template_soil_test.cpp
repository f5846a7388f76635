// template_soil_test: the built template_soil library, loaded the way the engine loads it
// (dlopen, the one exported entry point, the C function table), against the closed-form
// solution of its equation c u' + k u = F. Standard C++17 and the SDK headers only: no test
// framework, no engine. `ctest` runs it with the library's path as the argument; it prints each
// failed check and exits non-zero when there is one.
#include <dlfcn.h>
#include <rumble/abi.h>

#include <cmath>
#include <complex>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace {

constexpr const char* kType = "template_soil";
constexpr double kStiffness = 2.0e6;  // N/m
constexpr double kDamping = 1.0e5;    // N s/m: time constant c / k = 0.05 s
constexpr double kPi = 3.14159265358979323846;

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

/// One soil instance with two footprints, destroyed at the end of the scope.
class Soil {
 public:
  explicit Soil(const rumble_factory& f) : api_(static_cast<const rumble_soil_api*>(f.api)) {
    host_.struct_size = sizeof(rumble_host);
    host_.abi_minor = RUMBLE_ABI_MINOR;
    host_.scenario_dir = ".";
    const std::string params = "{\"stiffness\": " + std::to_string(kStiffness) +
                               ", \"damping\": " + std::to_string(kDamping) + "}";
    const char* error = nullptr;
    check(f.create(params.c_str(), &host_, &self_, &error) == RUMBLE_OK,
          std::string("create: ") + (error != nullptr ? error : ""));
    const rumble_footprint footprints[2] = {{0.0, 0.0, 2.6, 0.25}, {0.6, 0.0, 2.6, 0.25}};
    check(self_ != nullptr && api_->accept_layout(self_, footprints, 2) == RUMBLE_OK,
          "accept_layout");
  }
  ~Soil() {
    if (self_ != nullptr) api_->common.destroy(self_);
  }
  Soil(const Soil&) = delete;
  Soil& operator=(const Soil&) = delete;
  bool ok() const { return self_ != nullptr; }
  const rumble_soil_api& api() const { return *api_; }
  rumble_instance* self() const { return self_; }

 private:
  const rumble_soil_api* api_;
  rumble_host host_{};
  rumble_instance* self_ = nullptr;
};

// At rest under a static force F the spring carries it all: u = F / k.
void static_equilibrium(const rumble_factory& f) {
  Soil soil(f);
  if (!soil.ok()) return;
  const double force[2] = {8.0e4, 6.0e4};
  double u[2] = {0.0, 0.0};
  check(soil.api().initialize(soil.self(), 0.0, force, u, 2) == RUMBLE_OK, "initialize");
  check_close(u[0], force[0] / kStiffness, 1e-15, "static u[0]");
  check_close(u[1], force[1] / kStiffness, 1e-15, "static u[1]");
}

// From rest, a force F switched on at t = 0 and held: u(t) = F / k (1 - exp(-k t / c)) and
// v(t) = F / c exp(-k t / c), to round-off at the end of every macro step whatever its length, from
// steps much shorter than c / k (x = k H / c = 0.002, the series branch) to longer (x = 2).
void step_response(const rumble_factory& f) {
  const double force[2] = {8.0e4, 3.0e4};
  for (const double H : {1.0e-4, 5.0e-3, 2.0e-2, 0.1}) {
    Soil soil(f);
    if (!soil.ok()) return;
    const double none[2] = {0.0, 0.0};
    double u[2] = {0.0, 0.0}, v[2] = {0.0, 0.0};
    check(soil.api().initialize(soil.self(), 0.0, none, u, 2) == RUMBLE_OK, "initialize at 0");
    const rumble_waveform held{0, 2, force};  // order 0: the values are held over the step
    for (int step = 0; step < 10; ++step) {
      const double t = step * H;
      check(soil.api().advance(soil.self(), t, H, &held) == RUMBLE_OK, "advance");
      check(soil.api().motion(soil.self(), u, v, 2) == RUMBLE_OK, "motion");
      const double s = -(t + H) * kStiffness / kDamping;
      const std::string at =
          " at t = " + std::to_string(t + H) + " (H = " + std::to_string(H) + ")";
      for (int i = 0; i < 2; ++i) {
        check_close(u[i], -force[i] / kStiffness * std::expm1(s), 1e-12, "u" + at);
        // v = (F - k u) / c cancels as u nears F / k: its error scale is F / c, not v.
        check(std::abs(v[i] - force[i] / kDamping * std::exp(s)) <= 1e-12 * force[i] / kDamping,
              "v" + at + ": " + std::to_string(v[i]));
      }
    }
  }
}

// Footprints are independent springs and dashpots: H = diag(1 / (k + i omega c)).
void receptance(const rumble_factory& f) {
  Soil soil(f);
  if (!soil.ok()) return;
  const double f_hz = 12.5;
  double re[4] = {}, im[4] = {};
  check(soil.api().frequency_response(soil.self(), f_hz, re, im, 2) == RUMBLE_OK,
        "frequency_response");
  const std::complex<double> h = 1.0 / std::complex<double>(kStiffness, 2 * kPi * f_hz * kDamping);
  for (int k : {0, 3}) {
    check_close(re[k], h.real(), 1e-14, "Re H diagonal");
    check_close(im[k], h.imag(), 1e-14, "Im H diagonal");
  }
  check(re[1] == 0.0 && im[1] == 0.0 && re[2] == 0.0 && im[2] == 0.0, "H off-diagonal is zero");
}

// Params the schema would let through only by mistake are refused with what, the value, the fix.
void refuses_zero_damping(const rumble_factory& f) {
  rumble_host host{};
  host.struct_size = sizeof(rumble_host);
  rumble_instance* self = nullptr;
  const char* error = nullptr;
  check(f.create("{\"stiffness\": 1e8, \"damping\": 0}", &host, &self, &error) == RUMBLE_ERROR,
        "create with damping 0 fails");
  const std::string message = error != nullptr ? error : "";
  check(message == "params/damping: 0.000000 N s/m; must be > 0 (the model is first order in time)",
        "message: " + message);
  if (self != nullptr) static_cast<const rumble_soil_api*>(f.api)->common.destroy(self);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s <path of %s.so>\n", argv[0], kType);
    return 2;
  }
  const rumble_factory* f = load_factory(argv[1], RUMBLE_KIND_SOIL, kType);
  if (f == nullptr) return 1;
  static_equilibrium(*f);
  step_response(*f);
  receptance(*f);
  refuses_zero_damping(*f);
  if (failures == 0) std::printf("%s: all checks passed\n", kType);
  return failures == 0 ? 0 : 1;
}
