// Owning wrappers around plugin instances. Each keeps its library alive (shared_ptr), gives the
// plugin a host (logging to its own spdlog logger), and turns every status into engine behaviour:
// OK passes, WARNING is logged, DISCARD and ERROR/FATAL throw with the plugin's message.
#pragma once

#include <rumble/abi.h>

#include <complex>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "plugin/registry.hpp"

namespace spdlog {
class logger;
}

namespace rumble {

/// Thrown for RUMBLE_DISCARD: the call was refused and the instance is unchanged.
class Discarded : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Instance {
 public:
  /// label: where the component sits in the scenario, e.g. "/soil" or "/vehicles/1".
  /// Throws ConfigError when the plugin refuses the params (its message included).
  Instance(const ComponentType& type, std::string label, const nlohmann::json& params,
           const std::filesystem::path& scenario_dir);
  virtual ~Instance();
  Instance(const Instance&) = delete;
  Instance& operator=(const Instance&) = delete;

  const std::string& type_name() const { return type_.type_name; }
  const std::string& label() const { return label_; }
  const ComponentType& type() const { return type_; }

  std::size_t state_size() const;
  void save_state(std::vector<double>& buffer) const;  // resized once; no allocation after
  void restore_state(const std::vector<double>& buffer);

 protected:
  /// Throws RunError (ERROR/FATAL) or Discarded, naming the call and the plugin.
  rumble_status check(rumble_status status, const char* call) const;
  rumble_instance* handle() const { return handle_; }
  const rumble_common_api& common() const { return *common_; }

 private:
  static void log_callback(void* host_data, int32_t level, const char* message);
  ComponentType type_;  // a copy: the instance may outlive the registry; type_.library keeps
                        // the code (and the factory and tables it points to) mapped
  std::string label_;
  std::string scenario_dir_;
  std::shared_ptr<spdlog::logger> logger_;
  rumble_host host_{};
  const rumble_common_api* common_ = nullptr;
  rumble_instance* handle_ = nullptr;
};

class VehicleInstance final : public Instance {
 public:
  VehicleInstance(const ComponentType& type, std::string label, const nlohmann::json& params,
                  const std::filesystem::path& scenario_dir);
  std::size_t dof_count() const { return n_dof_; }
  const std::vector<rumble_wheel>& wheels() const { return wheels_; }
  void mass_matrix(const double* q, double* mass) const;
  void forces(double t, const double* q, const double* qd, double* f) const;
  void wheel_kinematics(const double* q, double* z, double* jacobian) const;
  /// False when the plugin offers no analytical tangent.
  bool tangent(double t, const double* q, const double* qd, double* k, double* c) const;
  std::vector<std::string> output_names() const;
  void outputs(double t, const double* q, const double* qd, double* values) const;

 private:
  const rumble_vehicle_api* api_;
  std::size_t n_dof_ = 0;
  std::vector<rumble_wheel> wheels_;
};

class SoilInstance final : public Instance {
 public:
  SoilInstance(const ComponentType& type, std::string label, const nlohmann::json& params,
               const std::filesystem::path& scenario_dir);
  void accept_layout(const std::vector<rumble_footprint>& footprints);
  void initialize(double t0, const std::vector<double>& static_force, std::vector<double>& u);
  void advance(double t, double H, const rumble_waveform& force);
  void motion(double* u, double* v, std::size_t n) const;
  /// False when the soil offers no frequency response. receptance: n x n, column-major.
  bool frequency_response(double f_hz, std::size_t n,
                          std::vector<std::complex<double>>& receptance);
  bool set_receivers(const std::vector<rumble_receiver>& receivers);
  void receiver_velocity(double* v, std::size_t n) const;

 private:
  const rumble_soil_api* api_;
  std::vector<double> re_, im_;  // scratch for frequency_response
};

class CouplerInstance final : public Instance {
 public:
  CouplerInstance(const ComponentType& type, std::string label, const nlohmann::json& params,
                  const std::filesystem::path& scenario_dir);
  /// Returns the coupler's status (ERROR when the host stopped it); never throws for ERROR so
  /// that the caller can tell a host stop from a coupler failure.
  rumble_status run(const rumble_cosim_host& host, double t0, double t_end, double H,
                    std::string& message);

 private:
  const rumble_coupler_api* api_;
};

}  // namespace rumble
