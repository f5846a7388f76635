// single_wheel: the seed paper's vehicle. One wheel (mass m) carrying a static load P that acts
// as a constant downward force (the sprung weight above the wheel, which is not modelled as a
// body), rolling at the scenario's speed.  One DOF: the wheel's vertical displacement z [m], down
// +.
//   m z'' = P + m g - F_contact
#include <rumble/params.hpp>
#include <rumble/plugin.hpp>
#include <string>
#include <vector>

namespace {

constexpr double kGravity = 9.81;  // m/s^2

class SingleWheel final : public rumble::Vehicle {
 public:
  static constexpr const char* kTypeName = "single_wheel";
  static constexpr const char* kSummary =
      "one wheel with a static load (sprung weight as a constant force), 1 DOF";
  /// Takes any step it is given (a coupler need not keep the other side's checkpoint for it).
  static constexpr std::uint64_t kCapabilities = rumble::kCapNeverRefuses;
  static const char* params_schema() {
    return R"schema({
  "type": "object",
  "additionalProperties": false,
  "required": ["mass", "static_load"],
  "properties": {
    "mass": {"type": "number", "minimum": 1, "maximum": 1e5,
             "description": "wheel (unsprung) mass [kg]; [1, 1e5] kg: half a wheelset is 500 to 1000 kg; 100 t is a whole loaded wagon"},
    "static_load": {"type": "number", "minimum": 0, "maximum": 1e6,
                    "description": "static load carried by the wheel, excluding its own weight [N]; [0, 1e6] N: wheel loads are 50 to 125 kN (heavy haul, 40 t axles, about 200 kN)"},
    "wheel_radius": {"type": "number", "minimum": 0.1, "maximum": 2, "default": 0.46,
                     "description": "rolling radius [m]; [0.1, 2] m: from small tram and bogie wheels (0.3 m) to the largest steam locomotive drivers (about 1.1 m)"}
  }
})schema";
  }

  SingleWheel(const std::string& params_json, const rumble::Host& /*host*/) {
    const rumble::Params p(params_json, params_schema());
    mass_ = p.get<double>("mass");
    load_ = p.get<double>("static_load");
    radius_ = p.get<double>("wheel_radius");
  }

  std::size_t dof_count() const override { return 1; }
  std::vector<rumble::Wheel> wheels() const override { return {rumble::Wheel{0.0, radius_}}; }
  void mass_matrix(const double*, double* m) override { m[0] = mass_; }
  void forces(double, const double*, const double*, double* f) override {
    f[0] = load_ + mass_ * kGravity;
  }
  void wheel_kinematics(const double* q, double* z, double* jacobian) override {
    z[0] = q[0];
    jacobian[0] = 1.0;
  }
  bool tangent(double, const double*, const double*, double* k, double* c) override {
    k[0] = 0.0;
    c[0] = 0.0;
    return true;
  }

 private:
  double mass_ = 0.0;    // kg
  double load_ = 0.0;    // N
  double radius_ = 0.0;  // m
};

}  // namespace

RUMBLE_PLUGIN("single_wheel", "0.1.0", SingleWheel)
