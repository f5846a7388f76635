// The explicit step's stability checks, shared by its tests: runs without load from a random
// displacement, which excites every mode of the mesh.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstdlib>

#include "time/explicit_solver.hpp"

namespace rumble::fem::test {

/// A random displacement of about 1e-6 m (Eigen's Random after srand(seed)), zero at the fixed
/// nodes, at rest.
inline ExplicitState random_state(const ExplicitSolver& op, unsigned seed) {
  std::srand(seed);
  ExplicitState s = op.rest_state();
  s.w = Eigen::VectorXd::Random(op.dofs()) * 1e-6;
  for (Eigen::Index k = 0; k < s.w.size(); ++k)
    if (op.fixed()[k / 3]) s.w[k] = 0.0;
  return s;
}

/// Largest kinetic + strain energy over the last 100 of `steps` steps of dt [s] from a random
/// state, over the largest over the first 100: about 1 while the step is stable (the modified
/// energy oscillates), huge (or not finite) where it is not.
inline double growth_from_random_state(const ExplicitSolver& op, double dt, int steps,
                                       unsigned seed = 11) {
  ExplicitState s = random_state(op, seed);
  const Eigen::VectorXd no_force = Eigen::VectorXd::Zero(op.dofs());
  double first = 0.0, last = 0.0;
  for (int k = 0; k < steps; ++k) {
    op.step(s, no_force, dt);
    const double e = op.kinetic_energy(s) + op.strain_energy(s);
    if (k < 100) first = std::max(first, e);
    if (k >= steps - 100) last = std::max(last, e);
  }
  return last / first;
}

/// Kinetic + strain energy after `steps` steps of dt [s] from a random state, over the first
/// step's.
inline double energy_after(const ExplicitSolver& op, double dt, int steps, unsigned seed = 11) {
  ExplicitState s = random_state(op, seed);
  const Eigen::VectorXd no_force = Eigen::VectorXd::Zero(op.dofs());
  op.step(s, no_force, dt);
  const double first = op.kinetic_energy(s) + op.strain_energy(s);
  for (int k = 1; k < steps; ++k) op.step(s, no_force, dt);
  return (op.kinetic_energy(s) + op.strain_energy(s)) / first;
}

}  // namespace rumble::fem::test
