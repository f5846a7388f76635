// The SDK's templates are only compiled when instantiated: this TU instantiates the boundary
// wrappers of all three kinds (RUMBLE_PLUGIN with a minimal vehicle, soil and coupler) under the
// strict warnings a plugin author may use (-Wconversion, -Wsign-conversion, ... see
// CMakeLists.txt), so that the SDK headers never warn in a plugin's build. Compiled, not run.
#include <rumble/coupling.hpp>
#include <rumble/newmark.hpp>
#include <rumble/params.hpp>
#include <rumble/plugin.hpp>
#include <string>
#include <vector>

namespace {

class MinimalVehicle final : public rumble::Vehicle {
 public:
  static constexpr const char* kTypeName = "sdk_check_vehicle";
  static constexpr const char* kSummary = "instantiation check";
  static const char* params_schema() { return "{}"; }
  MinimalVehicle(const std::string& params, const rumble::Host& /*host*/) {
    mass_ = rumble::Params(params).get_or<double>("mass", 1.0);
  }
  std::size_t dof_count() const override { return 1; }
  std::vector<rumble::Wheel> wheels() const override { return {rumble::Wheel{0.0, 0.46}}; }
  void mass_matrix(const double*, double* m) override { m[0] = mass_; }
  void forces(double, const double*, const double*, double* f) override { f[0] = 0.0; }
  void wheel_kinematics(const double* q, double* z, double* j) override {
    z[0] = q[0];
    j[0] = 1.0;
  }

 private:
  double mass_;  // kg
};

class MinimalSoil final : public rumble::Soil {
 public:
  static constexpr const char* kTypeName = "sdk_check_soil";
  static constexpr const char* kSummary = "instantiation check";
  static const char* params_schema() { return "{}"; }
  MinimalSoil(const std::string&, const rumble::Host&) {}
  void accept_layout(const std::vector<rumble::Footprint>& f) override { u_.resize(f.size()); }
  void initialize(double, const double*, double*) override {}
  void advance(double, double H, const rumble::Waveform& force) override {
    const rumble::Newmark newmark;
    for (std::size_t i = 0; i < u_.size(); ++i) u_[i] = force.at(i, 1.0) / newmark.c_a(H);
  }
  void motion(double* u, double* v) const override {
    for (std::size_t i = 0; i < u_.size(); ++i) u[i] = v[i] = u_[i];
  }

 private:
  std::vector<double> u_;
};

class MinimalCoupler final : public rumble::Coupler {
 public:
  static constexpr const char* kTypeName = "sdk_check_coupler";
  static constexpr const char* kSummary = "instantiation check";
  static const char* params_schema() { return "{}"; }
  MinimalCoupler(const std::string&, const rumble::Host&) {}
  void run(const rumble::CosimHost& host, double t0, double t_end, double H) override {
    using rumble::CosimHost;
    namespace coupling = rumble::coupling;
    coupling::OutputHistory soil(host, CosimHost::kSoil);
    const coupling::Link to_track(host, CosimHost::kSoil, CosimHost::kTrack);
    coupling::GroupResiduals residuals(host, CosimHost::kSoil);
    rumble::StepReport report;
    report.residuals.resize(residuals.groups());
    std::vector<double> wave, input;
    soil.sample(t0);
    for (std::size_t k = 0; k < coupling::macro_step_count(t0, t_end, H); ++k) {
      const double t = coupling::macro_step_start(t0, H, k);
      const double h = coupling::macro_step_length(t0, t_end, H, k);
      const std::uint32_t order = soil.extrapolate(2, t, h, wave);
      to_track.map(wave, order, input);
      host.set_input(CosimHost::kTrack, order, input);
      if (host.advance(CosimHost::kTrack, t, h) == RUMBLE_DISCARD)
        coupling::refused_step(host, t, h, CosimHost::kTrack, "instantiation check");
      soil.sample(t + h);
      residuals.measure_trial(wave, order, soil.latest(), report.residuals.data());
      residuals.measure(wave, order, soil.latest(), report.residuals.data());
      host.step_report(report);
    }
  }
};

}  // namespace

RUMBLE_PLUGIN("sdk_check", "0.0.0", MinimalVehicle, MinimalSoil, MinimalCoupler)
