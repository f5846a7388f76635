// Energy of the clm chain in free vibration, for the three soils of docs/physics.md §1.4 (E = 10,
// 155, 750 MPa, nu = 0.3, rho = 1800 kg/m^3) on 9 sleeper footprints.
//  * Undamped (the calibrated k_f, k_c with c_f = c_c = 0 and a mass m_f): Newmark's average
//    acceleration is the trapezoidal rule, which for a linear system is the implicit midpoint
//    rule, a Cayley transform that conserves E = (1/2) m_f |v|^2 + (1/2) u^T K u exactly: only
//    round-off may change it.
//  * Damped (the calibrated c_f, c_c as well): each step removes h vbar^T C vbar >= 0, vbar
//    the mean velocity over the step, so E never grows.
//  * Massless (the default clm from soil properties, nu = 0.3: Wolf's trapped mass is 0), under
//    a constant load: C = (C_z / K_z) K, so every footprint creeps monotonically to its static
//    displacement with time constant C_z / K_z (1.5 ms on the medium soil); the trapezoidal
//    rule keeps that (its factor per sub-step (1 - h/2a)/(1 + h/2a) is in (0, 1)).
// The release from a static deflection is the only excitation: the force jumps from its static
// value to 0 at t = 0. Every advance starts from a state consistent with the force at its start
// (u and v kept, a = M^-1 (F - C v - K u) recomputed), so the energy is conserved from the
// static state on: E_0 = (1/2) u0^T K u0, then at the end of each macro step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "soil_rig.hpp"

namespace rumble::soiltest {
namespace {

constexpr Index kEnergyN = 9, kEnergyMid = 4;
constexpr double kMass = 500.0;            // kg per footprint (a trapped soil mass of that order)
constexpr double kEnergyMacroStep = 1e-3;  // s
constexpr double kSoils[] = {10e6, 155e6, 750e6};  // E [Pa]

/// The chain's K (tridiagonal, end footprints with one neighbour).
Eigen::MatrixXd chain_stiffness(const Lumped& p) {
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(kEnergyN, kEnergyN);
  for (Index i = 0; i < kEnergyN; ++i) {
    K(i, i) = p.k_f;
    if (i > 0) K(i, i) += p.k_c, K(i, i - 1) = -p.k_c;
    if (i + 1 < kEnergyN) K(i, i) += p.k_c, K(i, i + 1) = -p.k_c;
  }
  return K;
}

double energy(const Motion& m, const Eigen::MatrixXd& K) {
  return 0.5 * kMass * m.v.squaredNorm() + 0.5 * m.u.dot(K * m.u);
}

/// Energies of the static state under 1e5 N at the middle footprint, then at the end of each
/// macro step after its release, over `periods` periods of the slowest mode (2 pi sqrt(m_f /
/// k_f), the uniform motion).
std::vector<double> free_vibration(const Lumped& p, double periods,
                                   double* max_kinetic_share = nullptr) {
  auto soil = make_soil("clm", clm_params(p), sleeper_row(kEnergyN));
  VectorXd F = VectorXd::Zero(kEnergyN);
  F[kEnergyMid] = 1e5;
  const VectorXd u0 = static_displacement(*soil, F);
  const Eigen::MatrixXd K = chain_stiffness(p);
  const double T = 2.0 * std::numbers::pi * std::sqrt(kMass / p.k_f);
  const auto steps = static_cast<long>(std::ceil(periods * T / kEnergyMacroStep));
  std::vector<double> E{0.5 * u0.dot(K * u0)};
  const VectorXd zero = VectorXd::Zero(kEnergyN);
  for (long s = 0; s < steps; ++s) {
    advance_held(*soil, static_cast<double>(s) * kEnergyMacroStep, kEnergyMacroStep, zero);
    const Motion now = motion(*soil, kEnergyN);
    E.push_back(energy(now, K));
    if (max_kinetic_share != nullptr) {
      *max_kinetic_share =
          std::max(*max_kinetic_share, 0.5 * kMass * now.v.squaredNorm() / E.front());
    }
  }
  return E;
}

Lumped calibrated(double E) {
  auto soil = make_soil("clm", soil_properties(E), sleeper_row(kEnergyN));
  return lumped_parameters(*soil, kEnergyN);
}

TEST(SoilChainEnergy, UndampedChainConservesEnergyToRoundOff) {
  for (const double E : kSoils) {
    Lumped p = calibrated(E);
    p.m_f = kMass;
    p.c_f = p.c_c = 0.0;
    double kinetic = 0.0;
    const std::vector<double> e = free_vibration(p, 50.0, &kinetic);
    // It does vibrate: the energy goes back and forth between u and v (a soil that did not move
    // would conserve it trivially).
    EXPECT_GT(kinetic, 0.5) << "E = " << E;
    double drift = 0.0;
    for (const double x : e) drift = std::max(drift, std::abs(x / e.front() - 1.0));
    std::printf("  E = %3.0f MPa: %zu macro steps, max |E_n / E_0 - 1| = %.1e\n", E / 1e6,
                e.size() - 1, drift);
    // Round-off: ~1e-16 per operation, a few per step, ~1e4 sub-steps, growing as a random
    // walk (~1e-14) or at worst linearly (~1e-12).
    EXPECT_LT(drift, 1e-11) << "E = " << E;
  }
}

TEST(SoilChainEnergy, DampedChainEnergyDecaysMonotonically) {
  for (const double E : kSoils) {
    Lumped p = calibrated(E);
    p.m_f = kMass;
    const std::vector<double> e = free_vibration(p, 10.0);
    for (std::size_t s = 1; s < e.size(); ++s) {
      ASSERT_LE(e[s], e[s - 1] * (1.0 + 1e-13)) << "E = " << E << ", macro step " << s;
    }
    std::printf("  E = %3.0f MPa: energy after 10 periods %.1e of the static one\n", E / 1e6,
                e.back() / e.front());
    // Damping ratio of the chain's modes >= 0.2 (c_f / 2 sqrt(k_f m_f) with the calibrated
    // dashpots): 10 periods leave far less than 1e-6 of the energy.
    EXPECT_LT(e.back(), 1e-6 * e.front()) << "E = " << E;
  }
}

TEST(SoilChainEnergy, MasslessChainCreepsToTheStaticSolutionWithoutOvershoot) {
  for (const double E : kSoils) {
    auto soil = make_soil("clm", soil_properties(E), sleeper_row(kEnergyN));
    VectorXd F = VectorXd::Zero(kEnergyN);
    F[kEnergyMid] = 1e5;  // N
    const VectorXd u_static = static_displacement(*soil, F);
    static_displacement(*soil, VectorXd::Zero(kEnergyN));  // start unloaded, at rest
    // 0.5 s: 80 time constants on the soft soil (C_z / K_z = 6.1 ms), more on the others.
    const long steps = 500;
    double overshoot = 0.0;
    for (long s = 0; s < steps; ++s) {
      advance_held(*soil, static_cast<double>(s) * kEnergyMacroStep, kEnergyMacroStep, F);
      const VectorXd u = motion(*soil, kEnergyN).u;
      for (Index i = 0; i < kEnergyN; ++i)
        overshoot = std::max(overshoot, std::abs(u[i]) / std::abs(u_static[i]) - 1.0);
    }
    const Motion end = motion(*soil, kEnergyN);
    const double error = (end.u - u_static).cwiseAbs().maxCoeff() / u_static.cwiseAbs().maxCoeff();
    std::printf(
        "  E = %3.0f MPa: max |u_i| / |u_static,i| - 1 = %+.1e, after 0.5 s |u - u_static| "
        "= %.1e of the peak\n",
        E / 1e6, overshoot, error);
    EXPECT_LE(overshoot, 1e-12) << "E = " << E;  // bounded by the static solution
    EXPECT_LT(error, 1e-9) << "E = " << E;       // e^-80 of the start, so round-off only
    // At rest: what the velocity would move in one macro step is round-off too.
    EXPECT_LT(end.v.cwiseAbs().maxCoeff() * kEnergyMacroStep,
              1e-9 * u_static.cwiseAbs().maxCoeff());
  }
}

}  // namespace
}  // namespace rumble::soiltest
