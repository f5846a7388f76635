// monolithic: the reference the co-simulation schemes are measured against (decision 0008). The
// host integrates the scenario's soil, from its linear matrices (M, C, K, B), inside the
// vehicle/track: both are stepped as one system by the track's Newmark integrator at the track's
// micro-step, the Hertz contacts solved by the track's Newton iteration as usual. There is no
// interface to iterate or extrapolate, so no co-simulation error: the difference between a
// gauss_seidel, jacobi, implicit or two_step run and this one on the same soil is exactly the
// error of that scheme.
//
// Each macro step is one advance of the track (the soil follows inside it) and a step report
// final for both; the macro step only sets how often the results are recorded. Needs a soil that
// gives its linear matrices (the lumped soils: winkler, clm); receivers and fields of the soil
// are not recorded (its footprint motion is).
#include <rumble/coupling.hpp>
#include <rumble/plugin.hpp>

namespace {

using rumble::CosimHost;

class Monolithic final : public rumble::Coupler {
 public:
  static constexpr const char* kTypeName = "monolithic";
  static constexpr const char* kSummary =
      "reference: the soil's linear matrices integrated with the vehicle/track as one system "
      "(no co-simulation error)";
  static constexpr std::uint64_t kCapabilities = rumble::kCapMonolithic;
  static constexpr std::uint64_t kSoilNeeds = rumble::kCapLinearMatrices;
  static const char* params_schema() {
    return R"schema({"type": "object", "additionalProperties": false, "properties": {}})schema";
  }

  Monolithic(const std::string& /*params_json*/, const rumble::Host& /*host*/) {}

  void run(const CosimHost& host, double t0, double t_end, double H) override {
    rumble::StepReport report;  // no residuals: nothing crosses an interface
    const std::size_t steps = rumble::coupling::macro_step_count(t0, t_end, H);
    for (std::size_t k = 0; k < steps; ++k) {
      report.t = rumble::coupling::macro_step_start(t0, H, k);
      report.H = rumble::coupling::macro_step_length(t0, t_end, H, k);
      if (host.advance(CosimHost::kTrack, report.t, report.H) == RUMBLE_DISCARD) {
        rumble::coupling::refused_step(host, report.t, report.H, CosimHost::kTrack,
                                       "monolithic does not retry steps");
      }
      host.step_report(report);
    }
  }
};

}  // namespace

RUMBLE_PLUGIN("monolithic", "0.1.0", Monolithic)
