// SPDX-License-Identifier: MIT
// rumble/plugin/vehicle.hpp (part of rumble/plugin.hpp): the Vehicle base class.
#ifndef RUMBLE_PLUGIN_VEHICLE_HPP
#define RUMBLE_PLUGIN_VEHICLE_HPP

#include <rumble/abi.h>

#include <cstddef>
#include <rumble/plugin/component.hpp>
#include <string>
#include <vector>

namespace rumble {

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
  /// Fill K = -df/dq, C = -df/dq' and return true. Overriding it declares an analytic tangent
  /// (ABI 1.1): return it at every state; a class without one does not override it, and the
  /// engine differentiates forces() numerically.
  virtual bool tangent(double /*t*/, const double* /*q*/, const double* /*qd*/,
                       double* /*stiffness*/, double* /*damping*/) {
    return false;
  }
  /// Optional output channels ("name [unit]"), written by outputs().
  virtual std::vector<std::string> output_names() const { return {}; }
  virtual void outputs(double /*t*/, const double* /*q*/, const double* /*qd*/,
                       double* /*values*/) {}
};

}  // namespace rumble

#endif  // RUMBLE_PLUGIN_VEHICLE_HPP
