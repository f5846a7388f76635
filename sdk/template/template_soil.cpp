// template_soil: the copy-me example of a Rumble soil plugin (see README.md next to this file).
//
// Model: every footprint i rests on its own spring (k) and dashpot (c) in parallel, fixed below:
//   c u_i' + k u_i = F_i(t)      (z down +: F_i > 0 pushes the footprint down, u_i > 0 is down)
// Over a macro step [t, t + H] the host gives F_i as a polynomial in tau = (s - t) / H of order
// 0..2, and this equation has a closed-form solution for such a force, so advance() integrates it
// exactly in one go (no sub-steps, no stability limit, any H):
//   u(t + H) = e^{-x} u(t) + (H / c) sum_k a_k psi_k(x),   x = k H / c,
//   psi_k(x) = int_0^1 e^{-x (1 - s)} s^k ds,
// where a_k are the waveform coefficients of F. The velocity then follows from the equation itself:
//   v = (F - k u) / c.
#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <rumble/params.hpp>
#include <rumble/plugin.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

constexpr double kPi = 3.14159265358979323846;

/// psi_0..psi_2 above. For small x the recurrence psi_k = (1 - k psi_{k-1}) / x cancels, so
/// the series psi_k = sum_m (-x)^m k! / (m + k + 1)! is used there instead.
std::array<double, 3> psi(double x) {
  std::array<double, 3> p{};
  if (x < 0.5) {
    for (std::size_t k = 0; k < p.size(); ++k) {
      double term = 1.0 / static_cast<double>(k + 1);
      double sum = term;
      for (std::size_t m = 1; m < 25; ++m) {  // 0.5^25 / 25! is far below double precision
        term *= -x / static_cast<double>(m + k + 1);
        sum += term;
      }
      p[k] = sum;
    }
  } else {
    p[0] = -std::expm1(-x) / x;
    for (std::size_t k = 1; k < p.size(); ++k) p[k] = (1.0 - static_cast<double>(k) * p[k - 1]) / x;
  }
  return p;
}

class TemplateSoil final : public rumble::Soil {
 public:
  static constexpr const char* kTypeName = "template_soil";
  static constexpr const char* kSummary = "one spring-dashpot per footprint, integrated exactly";
  /// It takes every step it is given (its advance never throws rumble::Discard) and says so, so
  /// that a coupler keeps no checkpoint of the other side for a refusal that cannot come (ABI
  /// 1.7). Drop it if your advance may refuse a step.
  static constexpr std::uint64_t kCapabilities = rumble::kCapNeverRefuses;
  static const char* params_schema() {
    return R"({
  "type": "object",
  "additionalProperties": false,
  "properties": {
    "stiffness": {"type": "number", "minimum": 1.0e4, "maximum": 1.0e13, "default": 1.0e8,
                  "description": "spring stiffness under each footprint [N/m]; [1e4, 1e13] N/m: a sleeper's footprint is about 1e6 N/m on peat and 1e10 N/m on hard rock"},
    "damping": {"type": "number", "exclusiveMinimum": 0, "maximum": 1.0e10, "default": 1.0e5,
                "description": "dashpot coefficient under each footprint [N s/m]; (0, 1e10] N s/m: a sleeper's footprint is about 2e4 N s/m on peat and 1e7 N s/m on hard rock"}
  }
})";
  }

  // Each default is declared once, in the schema: the host fills them, and Params given the
  // schema falls back to them when the host did not (a unit test).
  TemplateSoil(const std::string& params_json, const rumble::Host& host) : host_(host) {
    const rumble::Params p(params_json, params_schema());
    stiffness_ = p.get<double>("stiffness");
    damping_ = p.get<double>("damping");
    if (!(stiffness_ > 0.0)) {
      throw std::invalid_argument("params/stiffness: " + std::to_string(stiffness_) +
                                  " N/m; must be > 0 (a spring holds the static load)");
    }
    if (!(damping_ > 0.0)) {
      throw std::invalid_argument("params/damping: " + std::to_string(damping_) +
                                  " N s/m; must be > 0 (the model is first order in time)");
    }
  }

  void accept_layout(const std::vector<rumble::Footprint>& footprints) override {
    if (footprints.empty())
      throw std::invalid_argument("template_soil needs at least one footprint");
    u_.assign(footprints.size(), 0.0);
    v_.assign(footprints.size(), 0.0);
    host_.debug("template_soil: " + std::to_string(footprints.size()) + " footprints");
  }

  void initialize(double /*t0*/, const double* static_force, double* static_u) override {
    for (std::size_t i = 0; i < u_.size(); ++i) {
      u_[i] = static_force[i] / stiffness_;  // at rest: the dashpot carries nothing
      v_[i] = 0.0;
      static_u[i] = u_[i];
    }
  }

  void advance(double /*t*/, double H, const rumble::Waveform& force) override {
    if (force.channels() != u_.size()) {
      throw std::invalid_argument("advance: force has " + std::to_string(force.channels()) +
                                  " channels, the layout has " + std::to_string(u_.size()));
    }
    const double x = stiffness_ * H / damping_;
    const std::array<double, 3> w = psi(x);
    const double decay = std::exp(-x);
    for (std::size_t i = 0; i < u_.size(); ++i) {
      // Waveform::at(i, tau) is the polynomial; its coefficients a_k are recovered exactly from
      // three samples because the order is at most 2.
      const double f0 = force.at(i, 0.0), f_half = force.at(i, 0.5), f1 = force.at(i, 1.0);
      const double a0 = f0;
      const double a2 = 2.0 * (f1 - 2.0 * f_half + f0);
      const double a1 = f1 - f0 - a2;
      u_[i] = decay * u_[i] + H / damping_ * (a0 * w[0] + a1 * w[1] + a2 * w[2]);
      v_[i] = (f1 - stiffness_ * u_[i]) / damping_;
    }
  }

  void motion(double* u, double* v) const override {
    for (std::size_t i = 0; i < u_.size(); ++i) {
      u[i] = u_[i];
      v[i] = v_[i];
    }
  }

  /// Footprints are independent: the receptance is diagonal, 1 / (k + i omega c).
  bool frequency_response(double f_hz, std::complex<double>* receptance) override {
    const std::size_t n = u_.size();
    const double omega = 2.0 * kPi * f_hz;
    for (std::size_t k = 0; k < n * n; ++k) receptance[k] = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      receptance[i * n + i] = 1.0 / std::complex<double>(stiffness_, omega * damping_);
    return true;
  }

  // Save/restore (used by implicit and two-step couplers to repeat a macro step): u then v.
  std::size_t state_size() const override { return 2 * u_.size(); }
  void save_state(double* buffer) const override {
    for (std::size_t i = 0; i < u_.size(); ++i) {
      buffer[i] = u_[i];
      buffer[u_.size() + i] = v_[i];
    }
  }
  void restore_state(const double* buffer) override {
    for (std::size_t i = 0; i < u_.size(); ++i) {
      u_[i] = buffer[i];
      v_[i] = buffer[u_.size() + i];
    }
  }

 private:
  rumble::Host host_;
  double stiffness_ = 0.0;  // N/m
  double damping_ = 0.0;    // N s/m
  std::vector<double> u_;   // m, down +
  std::vector<double> v_;   // m/s, down +
};

}  // namespace

RUMBLE_PLUGIN("template_soil", "0.1.0", TemplateSoil)
