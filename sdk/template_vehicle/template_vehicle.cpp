// template_vehicle: the copy-me example of a Rumble vehicle plugin (see README.md next to this
// file). Start your own with `rumble new-plugin vehicle <name>`.
//
// Model: one rigid mass m on one wheel, carrying a static preload P besides its own weight (the
// part of the vehicle above the wheel, as a constant force). One DOF: the vertical displacement
// q of the mass [m], down +, which is also the wheel's contact point: z = q, J = dz/dq = 1.
//   m q'' = m g + P - F        (F >= 0 the contact force, pushing the wheel up)
// The engine integrates it with the track; the plugin only states M, f, z, J and the tangent.
// At rest the wheel carries F = m g + P.
#include <rumble/params.hpp>
#include <rumble/plugin.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

constexpr double kGravity = 9.81;  // m/s^2, acting in +z (down)

class TemplateVehicle final : public rumble::Vehicle {
 public:
  static constexpr const char* kTypeName = "template_vehicle";
  static constexpr const char* kSummary = "one mass on one wheel with a static preload, 1 DOF";
  /// It takes every step it is given (its advance never throws rumble::Discard) and says so, so
  /// that a coupler keeps no checkpoint of the other side for a refusal that cannot come (ABI
  /// 1.7). Drop it if your advance may refuse a step.
  static constexpr std::uint64_t kCapabilities = rumble::kCapNeverRefuses;
  static const char* params_schema() {
    return R"({
  "type": "object",
  "additionalProperties": false,
  "properties": {
    "mass": {"type": "number", "minimum": 1, "maximum": 1.0e5, "default": 1000.0,
             "description": "mass on the wheel [kg]; [1, 1e5] kg: a rail vehicle carries 0.5 to 15 t per wheel; 100 t is a whole loaded wagon"},
    "preload": {"type": "number", "minimum": 0, "maximum": 1.0e6, "default": 0.0,
                "description": "static load on the wheel besides the mass's own weight [N]; [0, 1e6] N: wheel loads are 50 to 125 kN, heavy haul with 40 t axles about 200 kN"},
    "wheel_radius": {"type": "number", "minimum": 0.1, "maximum": 2, "default": 0.46,
                     "description": "rolling radius [m]; [0.1, 2] m: from small tram and bogie wheels (0.3 m) to the largest steam locomotive drivers, about 1.1 m"}
  }
})";
  }

  // Each default is declared once, in the schema: the host fills them, and Params given the
  // schema falls back to them when the host did not (a unit test). The host also enforces the
  // ranges; the checks here only guard the divisions below against direct use, and say what,
  // the value and the fix.
  TemplateVehicle(const std::string& params_json, const rumble::Host& /*host*/) {
    const rumble::Params p(params_json, params_schema());
    mass_ = p.get<double>("mass");
    preload_ = p.get<double>("preload");
    radius_ = p.get<double>("wheel_radius");
    if (!(mass_ > 0.0)) {
      throw std::invalid_argument("params/mass: " + std::to_string(mass_) +
                                  " kg; must be > 0 (the wheel needs inertia)");
    }
    if (!(preload_ >= 0.0)) {
      throw std::invalid_argument("params/preload: " + std::to_string(preload_) +
                                  " N; must be >= 0 (a load pulling the wheel up lifts it)");
    }
  }

  std::size_t dof_count() const override { return 1; }
  std::vector<rumble::Wheel> wheels() const override { return {rumble::Wheel{0.0, radius_}}; }

  void mass_matrix(const double* /*q*/, double* mass) override { mass[0] = mass_; }

  // Gravity and the preload: constant, so the tangent below is zero.
  void forces(double /*t*/, const double* /*q*/, const double* /*qd*/, double* f) override {
    f[0] = mass_ * kGravity + preload_;
  }

  void wheel_kinematics(const double* q, double* z, double* jacobian) override {
    z[0] = q[0];
    jacobian[0] = 1.0;
  }

  // K = -df/dq, C = -df/dq': both zero. Given analytically, it spares the engine finite
  // differences of forces().
  bool tangent(double /*t*/, const double* /*q*/, const double* /*qd*/, double* stiffness,
               double* damping) override {
    stiffness[0] = 0.0;
    damping[0] = 0.0;
    return true;
  }

 private:
  double mass_ = 0.0;     // kg
  double preload_ = 0.0;  // N
  double radius_ = 0.0;   // m
};

}  // namespace

RUMBLE_PLUGIN("template_vehicle", "0.1.0", TemplateVehicle)
