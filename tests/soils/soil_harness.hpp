// soil_harness.hpp: the soil plugins as the engine drives them, for the tests. Each type's .so
// (RUMBLE_TEST_PLUGIN_DIR/<type>.so, only the ones a test uses) is loaded by the engine's
// PluginRegistry and each instance is a SoilInstance, the engine's wrapper: it gives the plugin
// the engine's host and turns every status into an exception quoting the plugin's message.
// The free functions on a SoilInstance are the steps every soil test takes (tests/soils/instance
// uses them through soil_rig.hpp); TestSoil keeps, on top of them, the status-and-message view
// of the plugin tests (tests/soils, tests/fem, tests/fem_mesh_file).
// Units: SI throughout, z down (abi.h): F > 0 [N] pushes the soil down, u > 0 [m] is downward.
#pragma once

#include <rumble/abi.h>

#include <Eigen/Dense>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "plugin/instance.hpp"
#include "plugin/registry.hpp"

namespace rumble::test {

using Eigen::MatrixXcd;
using Eigen::MatrixXd;
using Eigen::VectorXd;

/// The soil type `type` from RUMBLE_TEST_PLUGIN_DIR/<type>.so, loaded on first use (and never
/// unloaded); throws PluginLoadError when the file is missing or no plugin.
const ComponentType& soil_type(const std::string& type);
/// Its factory, as the plugin declared it (type name, params schema).
const rumble_factory& soil_factory(const std::string& type);

/// The plugin's message when it refuses these params at creation, "" when it accepts them.
std::string creation_error(const std::string& type, const std::string& params_json);

/// n whole-sleeper footprints on the track axis, x = i spacing [m], length (across) x width
/// (along) [m]; by default the 2.6 x 0.26 m sleepers at 0.6 m of docs/physics.md §1.1.
std::vector<rumble_footprint> sleeper_row(std::size_t n, double spacing = 0.6, double length = 2.6,
                                          double width = 0.26);

/// Static displacements [m] under the footprint forces F [N] (SoilInstance::initialize at t 0).
VectorXd static_displacement(SoilInstance& soil, const VectorXd& F);
/// Advance over [t, t + H] with a waveform of `order`: coeff[k n + i] (rumble_waveform).
void advance_waveform(SoilInstance& soil, double t, double H, unsigned order,
                      const VectorXd& coeff);
/// Advance with the force varying linearly from f0 (at t) to f1 (at t + H): an order-1
/// waveform, coefficients {f0, f1 - f0}.
void advance_linear(SoilInstance& soil, double t, double H, const VectorXd& f0, const VectorXd& f1);
/// Advance with the force held at f (order-0 waveform).
void advance_held(SoilInstance& soil, double t, double H, const VectorXd& f);

struct Motion {
  VectorXd u;  // m
  VectorXd v;  // m/s
};
Motion motion(const SoilInstance& soil, Eigen::Index n);

/// Receptance H(f) [m/N], n x n (u = H F, e^{+i w t}); throws when the soil offers none.
MatrixXcd receptance(SoilInstance& soil, double f_hz, Eigen::Index n);

/// One soil, a SoilInstance labelled "/soil" in the scenario directory ".", with the plugin's
/// statuses and messages in view: the try_ calls return the status the engine turned into an
/// exception and the plugin's own message (the engine's exception quotes it), and the others
/// throw the engine's exception (std::runtime_error) unless the plugin returns RUMBLE_OK (or
/// RUMBLE_WARNING, which the engine logs).
class TestSoil {
 public:
  TestSoil(const std::string& type, const std::string& params_json);
  ~TestSoil();
  TestSoil(const TestSoil&) = delete;
  TestSoil& operator=(const TestSoil&) = delete;

  /// The engine's wrapper, for the calls TestSoil does not name.
  SoilInstance& instance() { return *soil_; }

  /// accept_layout's status; the plugin's message in *message when not RUMBLE_OK.
  rumble_status try_accept_layout(const std::vector<rumble_footprint>& footprints,
                                  std::string* message);
  void accept_layout(const std::vector<rumble_footprint>& footprints);
  Eigen::Index size() const { return n_; }

  /// Static displacements [m] under the static footprint forces [N].
  VectorXd initialize(const VectorXd& static_force);
  /// Advance over [t, t + H] with a waveform of `order`: coeff[k n + i] (rumble_waveform).
  void advance(double t, double H, unsigned order, const VectorXd& coeff);
  /// Advance with the force varying linearly from f0 (at t) to f1 (at t + H).
  void advance_linear(double t, double H, const VectorXd& f0, const VectorXd& f1);
  /// Status of advance(); the plugin's message in *message when not RUMBLE_OK (the engine's
  /// own when it refused before calling the plugin: forces that are not finite).
  rumble_status try_advance(double t, double H, unsigned order, const VectorXd& coeff,
                            std::string* message);
  /// Drives a soil of one footprint from t = 0 to t_end in steps of H, the force [N] linear in
  /// each step from force(t) to force(t + H), and hands each probe sample to
  /// sample(t, probe, values): the RUMBLE_PROBE_VALUES values of probe `probe` at time t. The
  /// probes are the ones set through api() (read back through it too).
  void drive_probes(const std::function<double(double)>& force, double H, double t_end,
                    std::size_t probes,
                    const std::function<void(double, std::size_t, const double*)>& sample);
  VectorXd displacement();
  VectorXd velocity();
  /// Receptance H(f) [m/N], n x n.
  MatrixXcd receptance(double f_hz);

  /// The soil's state through the C table's save_state / restore_state (raw, as api()): the
  /// engine keeps checkpoints inside one instance (SoilInstance::checkpoint_*, reached through
  /// instance()), while this state can be read, sized and restored into another instance of
  /// the same layout, which is what the tests of it check.
  std::vector<double> save();
  void restore(const std::vector<double>& state);

  /// The raw C boundary of this same instance, for the tests of what the engine's wrapper does
  /// not let through (a status with its message as returned, the probes, the plugin's own
  /// checkpoints, calls counted for allocations). Calls made here bypass SoilInstance.
  const rumble_soil_api& api() const { return *api_; }
  rumble_instance* self() const { return self_; }

  /// What the soil logged through the engine's host while this TestSoil lived, in order (its
  /// type's spdlog logger, at the engine's log level: info and above by default; a soil of the
  /// same type alive at the same time would be heard too).
  const std::vector<std::string>& logs() const;
  /// The last logged message containing `text`, or "".
  std::string last_log(const std::string& text) const;
  /// Makes the soil part of a run writing into `dir` (the host's results_dir; "" until then, as
  /// in `rumble validate`).
  void set_results_dir(const std::string& dir);

 private:
  class LogCapture;
  void stop_listening();
  /// The plugin's message (when the engine's exception quotes it) and status for `e`, thrown
  /// by the engine's wrapper for `call`.
  rumble_status refusal(const std::exception& e, const char* call, std::string* message) const;
  std::shared_ptr<spdlog::logger> logger_;
  std::shared_ptr<LogCapture> logs_;  // one of logger_'s sinks while the soil lives
  std::unique_ptr<SoilInstance> soil_;
  const rumble_soil_api* api_ = nullptr;
  rumble_instance* self_ = nullptr;
  Eigen::Index n_ = 0;
};

}  // namespace rumble::test
