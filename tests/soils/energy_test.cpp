// Free vibration released from a static deflection, on the three soils. Newmark's average
// acceleration is the trapezoidal rule on (u, v); for M u'' + C u' + K u = 0 its discrete energy
// E = v'Mv/2 + u'Ku/2 changes per step by exactly -h v_m' C v_m (v_m the mid-step velocity):
// constant without damping, decreasing at every step with it.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "chain_calibration.hpp"
#include "soil_cases.hpp"
#include "soil_harness.hpp"

namespace rumble::test {
namespace {

constexpr Eigen::Index kN = 21;
constexpr double kMacroStep = 1e-3;  // s; the plugin sub-steps inside (default sub-step)
constexpr double kDuration = 0.2;    // s

struct Chain {
  double m, k, c, kc, cc;
};

/// v'Mv/2 + u'Ku/2 for a uniform chain [J].
double energy(const Chain& p, const VectorXd& u, const VectorXd& v) {
  double e = 0.5 * p.m * v.squaredNorm() + 0.5 * p.k * u.squaredNorm();
  for (Eigen::Index i = 0; i + 1 < u.size(); ++i) e += 0.5 * p.kc * std::pow(u[i + 1] - u[i], 2);
  return e;
}

/// A static load that excites every mode: 100 kN per footprint, uneven.
VectorXd static_load() {
  VectorXd F(kN);
  for (Eigen::Index i = 0; i < kN; ++i) F[i] = 1e5 * (1.0 + 0.5 * std::sin(1.3 * i));
  return F;
}

/// Energies after every macro step of a free vibration from the static deflection.
std::vector<double> free_vibration(const std::string& type, const nlohmann::json& params,
                                   const Chain& chain, double* max_kinetic_share) {
  TestSoil soil(type, params.dump());
  soil.accept_layout(sleeper_row(kN));
  VectorXd u = soil.initialize(static_load());
  std::vector<double> e = {energy(chain, u, VectorXd::Zero(kN))};
  *max_kinetic_share = 0.0;
  const VectorXd zero = VectorXd::Zero(kN);
  for (int k = 0; k < std::lround(kDuration / kMacroStep); ++k) {
    soil.advance_linear(k * kMacroStep, kMacroStep, zero, zero);
    u = soil.displacement();
    const VectorXd v = soil.velocity();
    e.push_back(energy(chain, u, v));
    *max_kinetic_share = std::max(*max_kinetic_share, 0.5 * chain.m * v.squaredNorm() / e[0]);
  }
  return e;
}

/// The medium soil's calibrated stiffnesses with a 500 kg participating mass per footprint.
Chain calibrated_chain(const Soil& s, bool damped) {
  const auto c = soils::calibrate_chain({s.E, s.nu, s.rho}, 2.6, 0.26, 0.6);
  return {500.0, c.k_f, damped ? c.c_f : 0.0, c.k_c, damped ? c.c_c : 0.0};
}

nlohmann::json clm_params(const Chain& c) {
  return {{"m_f", c.m}, {"k_f", c.k}, {"c_f", c.c}, {"k_c", c.kc}, {"c_c", c.cc}};
}

TEST(SoilEnergy, UndampedFreeVibrationConservesEnergy) {
  for (const Soil& s : kSoils) {
    SCOPED_TRACE(s.name);
    const Chain chain = calibrated_chain(s, false);
    double kinetic = 0.0;
    const std::vector<double> e = free_vibration("clm", clm_params(chain), chain, &kinetic);
    double drift = 0.0;
    for (const double x : e) drift = std::max(drift, std::abs(x - e[0]) / e[0]);
    // Round-off only: ~1e-16 per operation over a few thousand sub-steps.
    EXPECT_LT(drift, 1e-11);
    EXPECT_GT(kinetic, 0.3);  // it does vibrate: energy moves into motion
  }
}

TEST(SoilEnergy, DampedFreeVibrationDecaysAtEveryStep) {
  for (const Soil& s : kSoils) {
    for (const bool massive : {true, false}) {
      SCOPED_TRACE(std::string(s.name) + (massive ? " with mass" : " massless"));
      Chain chain = calibrated_chain(s, true);
      nlohmann::json params = soil_params(s);  // the calibrated CLM, dashpots included
      if (massive) {
        params["m_f"] = chain.m;
      } else {
        chain.m = 0.0;
      }
      double kinetic = 0.0;
      const std::vector<double> e = free_vibration("clm", params, chain, &kinetic);
      for (std::size_t k = 1; k < e.size(); ++k)
        ASSERT_LE(e[k], e[k - 1] * (1.0 + 1e-12)) << "step " << k;  // round-off margin
      // Slowest decay: the soft soil's massive chain, damping ratio ~0.3 at 110 rad/s, i.e.
      // energy ~ e^-15 after 0.2 s.
      EXPECT_LT(e.back(), 1e-4 * e.front());
    }
  }
}

TEST(SoilEnergy, DampedWinklerDecays) {
  for (const Soil& s : kSoils) {
    SCOPED_TRACE(s.name);
    nlohmann::json params = soil_params(s);
    params["m"] = 500.0;
    const auto f = soils::surface_footing({s.E, s.nu, s.rho}, 2.6, 0.26);
    const Chain chain{500.0, f.stiffness, f.dashpot, 0.0, 0.0};
    double kinetic = 0.0;
    const std::vector<double> e = free_vibration("winkler", params, chain, &kinetic);
    for (std::size_t k = 1; k < e.size(); ++k) ASSERT_LE(e[k], e[k - 1] * (1.0 + 1e-12));
    EXPECT_LT(e.back(), 1e-4 * e.front());
  }
}

}  // namespace
}  // namespace rumble::test
