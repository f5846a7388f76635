// dynamics.hpp: mass matrix and generalized forces of a Definition, from its Kinematics.
//   M(q)      = sum_b m_b (Jx^T Jx + Jz^T Jz) + I_yy,b Jr^T Jr
//   f(q, q')  = sum_b m_b g Jz^T                      gravity (+z)
//             - sum_b m_b (Jx^T a_cx + Jz^T a_cz)       quadratic velocity terms (J' q')
//             + sum_e F_e (J_b - J_a)^T n_e             spring-dampers (n_e: unit direction)
//             + sum_l P_l Jz(point)^T                   constant loads
// In the plane the rotational part has no quadratic term: Jr is constant and omega x I omega = 0.
#ifndef RUMBLE_MBS_DYNAMICS_HPP
#define RUMBLE_MBS_DYNAMICS_HPP

#include <cmath>
#include <complex>
#include <cstddef>
#include <vector>

#include "definition.hpp"
#include "kinematics.hpp"

namespace rumble::mbs {

/// Reference values at q = 0 that the elements and wheels measure from.
struct Nominal {
  std::vector<double> element_length;  // s0 per element [m]
  std::vector<double> wheel_z;         // wheel centre z at q = 0 [m]
  std::vector<double> wheel_x;         // wheel centre x at q = 0 [m]
};

/// Preallocated scratch for one scalar type.
template <class S>
struct Workspace {
  explicit Workspace(std::size_t n) : a(n), b(n) {}
  PointState<S> a, b;
};

/// Element e's compression force F [N] (see Element); adds F (J_b - J_a)^T n to f when f != null.
template <class S>
S element_force(const Element& e, double s0, const Kinematics<S>& kin, Workspace<S>& w, const S* qd,
                S* f) {
  kin.point(e.a, w.a);
  kin.point(e.b, w.b);
  const std::size_t n = kin.dof_count();
  S nx{}, nz{};  // unit direction of the element, pointing from a to b
  S s{};
  if (e.direction == Direction::kZ) {
    nz = 1.0;
    s = w.b.z - w.a.z;
  } else if (e.direction == Direction::kX) {
    nx = 1.0;
    s = w.b.x - w.a.x;
  } else {
    using std::sqrt;
    const S dx = w.b.x - w.a.x;
    const S dz = w.b.z - w.a.z;
    s = sqrt(dx * dx + dz * dz);
    nx = dx / s;
    nz = dz / s;
  }
  // s' = n . (v_b - v_a), with v = J q'.
  S rate{};
  for (std::size_t j = 0; j < n; ++j) {
    rate += (nx * (w.b.jx[j] - w.a.jx[j]) + nz * (w.b.jz[j] - w.a.jz[j])) * qd[j];
  }
  const S force = S(e.preload) - e.k * (s - s0) - e.c * rate;
  if (f != nullptr) {
    for (std::size_t j = 0; j < n; ++j) {
      f[j] += force * (nx * (w.b.jx[j] - w.a.jx[j]) + nz * (w.b.jz[j] - w.a.jz[j]));
    }
  }
  return force;
}

/// Generalized forces except contact; kin must be updated at (q, q').
template <class S>
void generalized_forces(const Definition& d, const Nominal& nominal, const Kinematics<S>& kin,
                        Workspace<S>& w, const S* qd, S* f) {
  const std::size_t n = kin.dof_count();
  for (std::size_t j = 0; j < n; ++j) f[j] = S{};
  for (std::size_t b = 0; b < d.bodies.size(); ++b) {
    const double m = d.bodies[b].mass;
    const S* jx = kin.jx(b);
    const S* jz = kin.jz(b);
    const S ax = kin.ax(b);
    const S az = kin.az(b);
    for (std::size_t j = 0; j < n; ++j) f[j] += m * (d.gravity * jz[j] - jx[j] * ax - jz[j] * az);
  }
  for (std::size_t e = 0; e < d.elements.size(); ++e) {
    element_force(d.elements[e], nominal.element_length[e], kin, w, qd, f);
  }
  for (const Load& l : d.loads) {
    kin.point(l.point, w.a);
    for (std::size_t j = 0; j < n; ++j) f[j] += l.force * w.a.jz[j];
  }
}

/// M(q), column-major; kin must be updated at q.
inline void mass_matrix(const Definition& d, const Kinematics<double>& kin, double* m) {
  const std::size_t n = kin.dof_count();
  for (std::size_t k = 0; k < n * n; ++k) m[k] = 0.0;
  for (std::size_t b = 0; b < d.bodies.size(); ++b) {
    const double mass = d.bodies[b].mass;
    const double inertia = d.bodies[b].inertia_yy;
    const double* jx = kin.jx(b);
    const double* jz = kin.jz(b);
    const double* jr = kin.jr(b);
    for (std::size_t c = 0; c < n; ++c) {
      for (std::size_t r = 0; r < n; ++r) {
        m[c * n + r] += mass * (jx[r] * jx[c] + jz[r] * jz[c]) + inertia * jr[r] * jr[c];
      }
    }
  }
}

}  // namespace rumble::mbs

#endif  // RUMBLE_MBS_DYNAMICS_HPP
