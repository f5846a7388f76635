// soil_harness.hpp: drive a soil plugin through its C table (rumble_soil_api), as the engine
// does, from the built .so in RUMBLE_TEST_PLUGIN_DIR.
#pragma once

#include <rumble/abi.h>

#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

namespace rumble::test {

using Eigen::MatrixXcd;
using Eigen::MatrixXd;
using Eigen::VectorXd;

/// The factory of a soil type, from <RUMBLE_TEST_PLUGIN_DIR>/<type>.so (loaded once, never
/// unloaded).
const rumble_factory& soil_factory(const std::string& type);

/// The error message create() returns for these params ("" when it succeeds).
std::string creation_error(const std::string& type, const std::string& params_json);

/// n whole-sleeper footprints on the track axis, x = i spacing [m], length (across) x width
/// (along) [m]; by default the 2.6 x 0.26 m sleepers at 0.6 m of docs/physics.md §1.1.
std::vector<rumble_footprint> sleeper_row(std::size_t n, double spacing = 0.6, double length = 2.6,
                                          double width = 0.26);

/// One soil instance created by the plugin's factory; calls other than try_accept_layout()
/// throw std::runtime_error with the plugin's message unless they return RUMBLE_OK.
class TestSoil {
 public:
  TestSoil(const std::string& type, const std::string& params_json);
  ~TestSoil();
  TestSoil(const TestSoil&) = delete;
  TestSoil& operator=(const TestSoil&) = delete;

  /// accept_layout's status; its message in *message when not RUMBLE_OK.
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
  /// Drives a soil of one footprint from t = 0 to t_end in steps of H, the force [N] linear in
  /// each step from force(t) to force(t + H), and hands each probe sample to
  /// sample(t, probe, values): the RUMBLE_PROBE_VALUES values of probe `probe` at time t.
  void drive_probes(const std::function<double(double)>& force, double H, double t_end,
                    std::size_t probes,
                    const std::function<void(double, std::size_t, const double*)>& sample);
  VectorXd displacement();
  VectorXd velocity();
  /// Receptance H(f) [m/N], n x n.
  MatrixXcd receptance(double f_hz);
  std::vector<double> save();
  void restore(const std::vector<double>& state);

  /// Status and message of advance(), for the refusals.
  rumble_status try_advance(double t, double H, unsigned order, const VectorXd& coeff,
                            std::string* message);

  const rumble_soil_api& api() const { return *api_; }
  rumble_instance* self() const { return self_; }
  /// The messages the soil logged through the host, in order.
  const std::vector<std::string>& logs() const { return logs_; }
  /// The last logged message containing `text`, or "".
  std::string last_log(const std::string& text) const;
  /// Makes the soil part of a run writing into `dir` (the host's results_dir; "" until then, as
  /// in `rumble validate`).
  void set_results_dir(const std::string& dir);

 private:
  void check(rumble_status status, const char* call) const;
  const rumble_soil_api* api_ = nullptr;
  rumble_instance* self_ = nullptr;
  rumble_host host_{};
  std::vector<std::string> logs_;
  std::string results_dir_;
  Eigen::Index n_ = 0;
};

}  // namespace rumble::test
