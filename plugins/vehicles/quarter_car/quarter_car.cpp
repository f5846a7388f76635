// quarter_car: one wheel under a chain of masses joined by linear spring-dampers, vertical only.
//   DOFs (down +, 0 = unloaded spring lengths): q0 wheel, q1 bogie, [q2 car body] [m].
//   M = diag(m_i);  f_i = m_i g + (static load on the top mass)
//                         + compression of the stage above i - compression of the stage below i
// The springs carry no preload: under gravity the masses settle by their static deflection, which
// the engine's static solution finds. All values per wheel (one rail).
#include <array>
#include <cstddef>
#include <rumble/plugin.hpp>
#include <string>
#include <vector>

#include "quarter_car_params.hpp"

namespace rumble::vehicles {
namespace {

constexpr std::size_t kMaxMasses = 3;

class QuarterCar final : public rumble::Vehicle {
 public:
  static constexpr const char* kTypeName = "quarter_car";
  static constexpr const char* kSummary =
      "wheel + primary suspension + bogie [+ secondary suspension + car body], vertical, per "
      "wheel; 2 or 3 DOFs";
  /// Takes any step it is given (a coupler need not keep the other side's checkpoint for it).
  static constexpr std::uint64_t kCapabilities = rumble::kCapNeverRefuses;
  static const char* params_schema() { return quarter_car_schema(); }

  QuarterCar(const std::string& params_json, const rumble::Host& /*host*/) {
    const QuarterCarParams p = parse_quarter_car_params(params_json);
    masses_ = {p.wheel_mass, p.bogie_mass, 0.0};
    stages_ = {p.primary, SpringDamper{}};
    n_ = 2;
    if (p.secondary) {
      masses_[2] = p.secondary->car_body_mass;
      stages_[1] = p.secondary->suspension;
      n_ = 3;
    }
    static_load_ = p.static_load;
    radius_ = p.wheel_radius;
    gravity_ = p.gravity;
  }

  std::size_t dof_count() const override { return n_; }
  std::vector<rumble::Wheel> wheels() const override { return {rumble::Wheel{0.0, radius_}}; }

  void mass_matrix(const double* /*q*/, double* m) override {
    for (std::size_t k = 0; k < n_ * n_; ++k) m[k] = 0.0;
    for (std::size_t i = 0; i < n_; ++i) m[i * n_ + i] = masses_[i];
  }

  void forces(double /*t*/, const double* q, const double* qd, double* f) override {
    for (std::size_t i = 0; i < n_; ++i) f[i] = masses_[i] * gravity_;
    f[n_ - 1] += static_load_;
    for (std::size_t s = 0; s + 1 < n_; ++s) {
      const double compression = stage_force(s, q, qd);  // N
      f[s] += compression;                               // pushes the lower mass down
      f[s + 1] -= compression;                           // and the upper mass up
    }
  }

  void wheel_kinematics(const double* q, double* z, double* jacobian) override {
    z[0] = q[0];
    for (std::size_t i = 0; i < n_; ++i) jacobian[i] = i == 0 ? 1.0 : 0.0;
  }

  bool tangent(double /*t*/, const double* /*q*/, const double* /*qd*/, double* k,
               double* c) override {
    for (std::size_t e = 0; e < n_ * n_; ++e) k[e] = c[e] = 0.0;
    for (std::size_t s = 0; s + 1 < n_; ++s) {
      add_stage(k, s, stages_[s].k);
      add_stage(c, s, stages_[s].c);
    }
    return true;
  }

  std::vector<std::string> output_names() const override {
    std::vector<std::string> names{"primary_force [N]"};
    if (n_ == 3) names.emplace_back("secondary_force [N]");
    return names;
  }
  void outputs(double /*t*/, const double* q, const double* qd, double* values) override {
    for (std::size_t s = 0; s + 1 < n_; ++s) values[s] = stage_force(s, q, qd);
  }

 private:
  /// Compression of stage s [N] (positive when it carries weight): k (q_{s+1} - q_s) + c (...)'.
  /// It pushes the lower mass s down and the upper mass s+1 up.
  double stage_force(std::size_t s, const double* q, const double* qd) const {
    return stages_[s].k * (q[s + 1] - q[s]) + stages_[s].c * (qd[s + 1] - qd[s]);
  }
  /// Adds value * [[1, -1], [-1, 1]] on DOFs (s, s+1) of an n x n column-major matrix.
  void add_stage(double* a, std::size_t s, double value) const {
    a[s * n_ + s] += value;
    a[(s + 1) * n_ + s + 1] += value;
    a[(s + 1) * n_ + s] -= value;
    a[s * n_ + s + 1] -= value;
  }

  std::array<double, kMaxMasses> masses_{};          // kg: wheel, bogie, car body
  std::array<SpringDamper, kMaxMasses - 1> stages_;  // primary, secondary
  std::size_t n_ = 2;                                // DOFs
  double static_load_ = 0.0;                         // N
  double radius_ = 0.0;                              // m
  double gravity_ = 0.0;                             // m/s^2
};

}  // namespace
}  // namespace rumble::vehicles

RUMBLE_PLUGIN("quarter_car", "0.1.0", rumble::vehicles::QuarterCar)
