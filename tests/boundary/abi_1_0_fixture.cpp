// A vehicle, a soil and a coupler written against the ABI 1.0 C++ SDK and nothing newer, so that
// the same source builds as a 1.0 plugin (against the frozen headers in tests/abi/v1_0) and as a
// 1.1 plugin (against sdk/include). FIXTURE_SUFFIX ("_1_0" or "_1_1") keeps the type names apart.
//   fixture_wheel: m z'' = P + m g - F (the single_wheel model)
//   fixture_soil:  c u' + k u = F per footprint, backward Euler in 8 sub-steps per advance
//   fixture_coupler: Gauss-Seidel, track first, order 0, written as a 1.0 coupler had to be:
//                    it knows that the soil's outputs are u then v (output_size / 2)
#include <cmath>
#include <complex>
#include <rumble/params.hpp>
#include <rumble/plugin.hpp>
#include <string>
#include <vector>

#ifndef FIXTURE_SUFFIX
#error "define FIXTURE_SUFFIX"
#endif

namespace {

class FixtureWheel final : public rumble::Vehicle {
 public:
  static constexpr const char* kTypeName = "fixture_wheel" FIXTURE_SUFFIX;
  static constexpr const char* kSummary = "ABI 1.0 fixture: one wheel with a static load";
  static const char* params_schema() {
    return R"({"type": "object", "additionalProperties": false,
  "properties": {"mass": {"type": "number", "exclusiveMinimum": 0, "default": 750},
                 "static_load": {"type": "number", "minimum": 0, "default": 50000}}})";
  }
  FixtureWheel(const std::string& params, const rumble::Host&) {
    const rumble::Params p(params);
    mass_ = p.get<double>("mass");
    load_ = p.get<double>("static_load");
  }
  std::size_t dof_count() const override { return 1; }
  std::vector<rumble::Wheel> wheels() const override { return {rumble::Wheel{0.0, 0.46}}; }
  void mass_matrix(const double*, double* m) override { m[0] = mass_; }
  void forces(double, const double*, const double*, double* f) override {
    f[0] = load_ + mass_ * 9.81;
  }
  void wheel_kinematics(const double* q, double* z, double* j) override {
    z[0] = q[0];
    j[0] = 1.0;
  }
  std::vector<std::string> output_names() const override { return {"z [m]", "z' [m/s]"}; }
  void outputs(double, const double* q, const double* qd, double* values) override {
    values[0] = q[0];
    values[1] = qd[0];
  }

 private:
  double mass_ = 0.0, load_ = 0.0;  // kg, N
};

class FixtureSoil final : public rumble::Soil {
 public:
  static constexpr const char* kTypeName = "fixture_soil" FIXTURE_SUFFIX;
  static constexpr const char* kSummary = "ABI 1.0 fixture: spring-dashpot per footprint";
  static const char* params_schema() {
    return R"({"type": "object", "additionalProperties": false,
  "properties": {"k": {"type": "number", "exclusiveMinimum": 0, "default": 1.0e8},
                 "c": {"type": "number", "exclusiveMinimum": 0, "default": 2.0e5}}})";
  }
  FixtureSoil(const std::string& params, const rumble::Host&) {
    const rumble::Params p(params);
    k_ = p.get<double>("k");
    c_ = p.get<double>("c");
  }
  void accept_layout(const std::vector<rumble::Footprint>& f) override {
    u_.assign(f.size(), 0.0);
    v_.assign(f.size(), 0.0);
  }
  void initialize(double, const double* force, double* u) override {
    for (std::size_t i = 0; i < u_.size(); ++i) u[i] = u_[i] = force[i] / k_;
  }
  void advance(double, double H, const rumble::Waveform& force) override {
    constexpr int kSub = 8;
    const double h = H / kSub;
    for (int s = 1; s <= kSub; ++s) {
      for (std::size_t i = 0; i < u_.size(); ++i) {
        const double f = force.at(i, static_cast<double>(s) / kSub);
        const double u = (c_ * u_[i] + h * f) / (c_ + h * k_);
        v_[i] = (u - u_[i]) / h;
        u_[i] = u;
      }
    }
  }
  void motion(double* u, double* v) const override {
    for (std::size_t i = 0; i < u_.size(); ++i) {
      u[i] = u_[i];
      v[i] = v_[i];
    }
  }
  bool frequency_response(double f_hz, std::complex<double>* h) override {
    const std::size_t n = u_.size();
    for (std::size_t j = 0; j < n * n; ++j) h[j] = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      h[i * n + i] = 1.0 / std::complex<double>(k_, 2.0 * 3.141592653589793 * f_hz * c_);
    return true;
  }
  std::size_t state_size() const override { return 2 * u_.size(); }
  void save_state(double* b) const override {
    for (std::size_t i = 0; i < u_.size(); ++i) {
      b[i] = u_[i];
      b[u_.size() + i] = v_[i];
    }
  }
  void restore_state(const double* b) override {
    for (std::size_t i = 0; i < u_.size(); ++i) {
      u_[i] = b[i];
      v_[i] = b[u_.size() + i];
    }
  }

 private:
  double k_ = 0.0, c_ = 0.0;  // N/m, N s/m
  std::vector<double> u_, v_;
};

class FixtureCoupler final : public rumble::Coupler {
 public:
  static constexpr const char* kTypeName = "fixture_coupler" FIXTURE_SUFFIX;
  static constexpr const char* kSummary = "ABI 1.0 fixture: Gauss-Seidel, order 0";
  static const char* params_schema() { return R"({"type": "object"})"; }
  FixtureCoupler(const std::string&, const rumble::Host&) {}
  void run(const rumble::CosimHost& host, double t0, double t_end, double H) override {
    using C = rumble::CosimHost;
    std::vector<double> soil_out(host.output_size(C::kSoil)), force(host.interface_size());
    host.get_output(C::kSoil, soil_out);
    const auto steps = static_cast<std::size_t>(std::ceil((t_end - t0) / H - 1e-9));
    for (std::size_t k = 0; k < steps; ++k) {
      const double t = t0 + static_cast<double>(k) * H;
      const double h = std::fmin(H, t_end - t);
      const std::vector<double> used = soil_out;
      host.set_input(C::kTrack, 0, soil_out);
      host.advance(C::kTrack, t, h);
      host.get_output(C::kTrack, force);
      host.set_input(C::kSoil, 0, force);
      host.advance(C::kSoil, t, h);
      host.get_output(C::kSoil, soil_out);
      double diff = 0.0, scale = 0.0;  // on u only: the first half of the soil's outputs
      for (std::size_t i = 0; i < soil_out.size() / 2; ++i) {
        diff = std::fmax(diff, std::fabs(used[i] - soil_out[i]));
        scale = std::fmax(scale, std::fabs(soil_out[i]));
      }
      host.step_done(t, h, scale > 0.0 ? diff / scale : diff);
    }
  }
};

}  // namespace

RUMBLE_PLUGIN("abi_fixture" FIXTURE_SUFFIX, "1.0.0", FixtureWheel, FixtureSoil, FixtureCoupler)
