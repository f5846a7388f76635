// SPDX-License-Identifier: MIT
// rumble/newmark.hpp: the Newmark-beta time integrator, in one place for the engine's track and
// every plugin (soils, ...). Header-only, standard library only; works on any vector type with
// element access and size() (std::vector, Eigen vectors).
//
// For M a + C v + K x = f, one step of size h solves K_eff x1 = f1 + M pa + C pv with
//   K_eff = K + c_v C + c_a M,     c_a = 1/(beta h^2),  c_v = gamma/(beta h),
//   pa    = c_a x0 + v0/(beta h) + (1/(2 beta) - 1) a0,
//   pv    = c_v x0 + (gamma/beta - 1) v0 + h (gamma/(2 beta) - 1) a0,
// then a1 = c_a (x1 - x0) - v0/(beta h) - (1/(2 beta) - 1) a0 and v1 = v0 + h((1-gamma) a0 + gamma
// a1). beta = 1/4, gamma = 1/2 (average acceleration, the default) is unconditionally stable,
// second order and conserves the energy of an undamped linear system exactly; gamma > 1/2 with beta
// = (gamma + 1/2)^2 / 4 adds numerical damping of high frequencies.
#ifndef RUMBLE_NEWMARK_HPP
#define RUMBLE_NEWMARK_HPP

#include <cstddef>

namespace rumble {

struct Newmark {
  double beta = 0.25;
  double gamma = 0.5;

  double c_a(double h) const { return 1.0 / (beta * h * h); }
  double c_v(double h) const { return gamma / (beta * h); }

  /// Writes pa and pv (see above) from the state at the start of the step.
  template <class V, class W>
  void predictors(double h, const V& x0, const V& v0, const V& a0, W& pa, W& pv) const {
    const double ca = c_a(h), cv = c_v(h);
    for (std::size_t i = 0; i < static_cast<std::size_t>(x0.size()); ++i) {
      pa[i] = ca * x0[i] + v0[i] / (beta * h) + (0.5 / beta - 1.0) * a0[i];
      pv[i] = cv * x0[i] + (gamma / beta - 1.0) * v0[i] + h * (0.5 * gamma / beta - 1.0) * a0[i];
    }
  }

  /// Velocity and acceleration at the end of the step from x1; v and a hold v0, a0 on entry.
  template <class V>
  void correct(double h, const V& x0, const V& x1, V& v, V& a) const {
    const double ca = c_a(h);
    for (std::size_t i = 0; i < static_cast<std::size_t>(x0.size()); ++i) {
      const double a1 = ca * (x1[i] - x0[i]) - v[i] / (beta * h) - (0.5 / beta - 1.0) * a[i];
      v[i] += h * ((1.0 - gamma) * a[i] + gamma * a1);
      a[i] = a1;
    }
  }
};

}  // namespace rumble

#endif  // RUMBLE_NEWMARK_HPP
