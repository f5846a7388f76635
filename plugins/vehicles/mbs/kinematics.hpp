// kinematics.hpp: poses, Jacobians and convective accelerations of the bodies, by walking each
// body's chain of homogeneous transformations (planar: x forward, z down, pitch about y).
//
// Along a chain the frame has origin p, angle theta and angular velocity omega; the rotation
// R(theta) = [[cos, sin], [-sin, cos]] maps frame coordinates (x, z) to the reference frame
// (positive theta lifts the front). A step changes them as follows (a = nominal + q_dof):
//   rotation    theta += a,  omega += a',  d theta / d q_dof += 1
//   translation along the frame's unit axis e, u = R e, d = u a:
//               p += d,  dp/dq += S d (dtheta/dq) + u [j == dof],  with S d = (d_z, -d_x)
//               a_c += -omega^2 d + 2 omega S u a'
// where a_c is the convective acceleration (the acceleration with q'' = 0, i.e. J' q'). These are
// the exact chain-rule derivatives: Jacobians and a_c carry no truncation error. The class is a
// template so that the same code runs on complex numbers for complex-step tangents.
#ifndef RUMBLE_MBS_KINEMATICS_HPP
#define RUMBLE_MBS_KINEMATICS_HPP

#include <cmath>
#include <complex>
#include <cstddef>
#include <vector>

#include "definition.hpp"

namespace rumble::mbs {

/// A point's position [m], convective acceleration [m/s^2] and Jacobian rows (n each).
template <class S>
struct PointState {
  explicit PointState(std::size_t n) : jx(n), jz(n) {}
  S x{}, z{};
  S ax{}, az{};
  std::vector<S> jx, jz;  // d x / d q, d z / d q
};

template <class S>
class Kinematics {
 public:
  explicit Kinematics(const Definition& d)
      : d_(d),
        n_(d.dof_names.size()),
        x_(d.bodies.size()),
        z_(d.bodies.size()),
        theta_(d.bodies.size()),
        omega_(d.bodies.size()),
        ax_(d.bodies.size()),
        az_(d.bodies.size()),
        jx_(d.bodies.size() * n_),
        jz_(d.bodies.size() * n_),
        jr_(d.bodies.size() * n_) {}

  std::size_t dof_count() const { return n_; }

  /// Every body's state at (q, q'); no allocation.
  void update(const S* q, const S* qd) {
    for (const int b : d_.order) update_body(static_cast<std::size_t>(b), q, qd);
  }

  // Body b's centre of mass (the frame origin) after update().
  const S& x(std::size_t b) const { return x_[b]; }
  const S& z(std::size_t b) const { return z_[b]; }
  const S& ax(std::size_t b) const { return ax_[b]; }
  const S& az(std::size_t b) const { return az_[b]; }
  const S* jx(std::size_t b) const { return &jx_[b * n_]; }
  const S* jz(std::size_t b) const { return &jz_[b * n_]; }
  const S* jr(std::size_t b) const { return &jr_[b * n_]; }

  /// A point fixed on a body (or on the reference frame), after update().
  void point(const BodyPoint& p, PointState<S>& out) const {
    if (p.body == kReference) {
      out.x = p.x;
      out.z = p.z;
      out.ax = out.az = S{};
      for (std::size_t j = 0; j < n_; ++j) out.jx[j] = out.jz[j] = S{};
      return;
    }
    using std::cos;
    using std::sin;
    const auto b = static_cast<std::size_t>(p.body);
    const S c = cos(theta_[b]);
    const S s = sin(theta_[b]);
    const S dx = c * p.x + s * p.z;  // R (x, z), m
    const S dz = -s * p.x + c * p.z;
    out.x = x_[b] + dx;
    out.z = z_[b] + dz;
    const S w2 = omega_[b] * omega_[b];
    out.ax = ax_[b] - w2 * dx;
    out.az = az_[b] - w2 * dz;
    for (std::size_t j = 0; j < n_; ++j) {
      out.jx[j] = jx_[b * n_ + j] + dz * jr_[b * n_ + j];
      out.jz[j] = jz_[b * n_ + j] - dx * jr_[b * n_ + j];
    }
  }

 private:
  void update_body(std::size_t b, const S* q, const S* qd) {
    const int parent = d_.bodies[b].parent;
    if (parent == kReference) {
      x_[b] = z_[b] = theta_[b] = omega_[b] = ax_[b] = az_[b] = S{};
      for (std::size_t j = 0; j < n_; ++j)
        jx_[b * n_ + j] = jz_[b * n_ + j] = jr_[b * n_ + j] = S{};
    } else {
      const auto p = static_cast<std::size_t>(parent);
      x_[b] = x_[p];
      z_[b] = z_[p];
      theta_[b] = theta_[p];
      omega_[b] = omega_[p];
      ax_[b] = ax_[p];
      az_[b] = az_[p];
      for (std::size_t j = 0; j < n_; ++j) {
        jx_[b * n_ + j] = jx_[p * n_ + j];
        jz_[b * n_ + j] = jz_[p * n_ + j];
        jr_[b * n_ + j] = jr_[p * n_ + j];
      }
    }
    for (const Transform& t : d_.bodies[b].transforms) apply(b, t, q, qd);
  }

  void apply(std::size_t b, const Transform& t, const S* q, const S* qd) {
    const bool driven = t.dof != kNoDof;
    const auto dof = static_cast<std::size_t>(driven ? t.dof : 0);
    const S a = driven ? S(t.value) + q[dof] : S(t.value);
    const S rate = driven ? qd[dof] : S{};
    if (t.motion == Motion::kRotateY) {
      theta_[b] += a;
      omega_[b] += rate;
      if (driven) jr_[b * n_ + dof] += 1.0;
      return;
    }
    using std::cos;
    using std::sin;
    const S c = cos(theta_[b]);
    const S s = sin(theta_[b]);
    // u = R e: e = (1, 0) gives (c, -s), e = (0, 1) gives (s, c).
    const S ux = t.motion == Motion::kTranslateX ? c : s;
    const S uz = t.motion == Motion::kTranslateX ? -s : c;
    const S dx = ux * a;
    const S dz = uz * a;
    x_[b] += dx;
    z_[b] += dz;
    for (std::size_t j = 0; j < n_; ++j) {
      jx_[b * n_ + j] += dz * jr_[b * n_ + j];
      jz_[b * n_ + j] -= dx * jr_[b * n_ + j];
    }
    if (driven) {
      jx_[b * n_ + dof] += ux;
      jz_[b * n_ + dof] += uz;
    }
    const S w = omega_[b];
    ax_[b] += -w * w * dx + 2.0 * w * uz * rate;  // S u = (u_z, -u_x)
    az_[b] += -w * w * dz - 2.0 * w * ux * rate;
  }

  const Definition& d_;
  std::size_t n_;
  std::vector<S> x_, z_, theta_, omega_, ax_, az_;  // per body
  std::vector<S> jx_, jz_, jr_;                     // per body, n each
};

}  // namespace rumble::mbs

#endif  // RUMBLE_MBS_KINEMATICS_HPP
