#include "operator/element_stiffness.hpp"

#include <omp.h>

#include <algorithm>
#include <array>

namespace rumble::fem {

ElementStiffness::ElementStiffness(const TetMesh& mesh, const FemSettings& settings) : mesh_(mesh) {
  const double relaxed = settings.damping.relaxed_modulus_factor();
  for (const soils::SoilLayer& layer : settings.layers)
    lame_.push_back(lame_of(layer.properties, relaxed));
  lame_.push_back(lame_of(settings.half_space, relaxed));
}

void ElementStiffness::sort_tetrahedra() const {
  if (!tets_.empty() || mesh_.tets.empty()) return;
  std::vector<std::int64_t> keyed(mesh_.tets.size());  // (lowest node << 32 | tetrahedron)
  for (std::size_t e = 0; e < keyed.size(); ++e) {
    const Tetrahedron& t = mesh_.tets[e];
    keyed[e] = (static_cast<std::int64_t>(*std::min_element(t.begin(), t.end())) << 32) |
               static_cast<std::int64_t>(e);
  }
  std::sort(keyed.begin(), keyed.end());
  tets_.reserve(keyed.size());
  layer_.reserve(keyed.size());
  for (const std::int64_t key : keyed) {
    const auto e = static_cast<std::size_t>(key & 0xffffffff);
    tets_.push_back(mesh_.tets[e]);  // (tet_properties' choice of layer: the last the half-space)
    layer_.push_back(
        static_cast<std::uint16_t>(std::min<std::size_t>(mesh_.layer[e], lame_.size() - 1)));
  }
}

namespace {

using Vec3 = std::array<double, 3>;

Vec3 minus(const double* a, const double* b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// Adds tetrahedron t's K_e u_e to y (u: a displacement, 3 per node). With the edges
// e_k = p_k - p_0 (k = 1..3, p the nodes' positions) as J's columns, J^-1's rows are
// n_1 = e_2 x e_3, n_2 = e_3 x e_1, n_3 = e_1 x e_2 over det J = e_1 . n_1, so g_k = n_k / det and
// g_0 = -(g_1 + g_2 + g_3). With V = det / 6 one division does: G = sum_k (u_k - u_0) n_k^T / det,
// f_k = V sigma g_k = sigma~ n_k / (6 det) for sigma~ the stress of det G, and
// f_0 = -(f_1 + f_2 + f_3) (the element's forces balance).
void add_element(const double* nodes, const Tetrahedron& t, const Lame& m, const double* u,
                 double* y) {
  const double* p0 = nodes + 3 * t[0];
  const Vec3 e1 = minus(nodes + 3 * t[1], p0), e2 = minus(nodes + 3 * t[2], p0),
             e3 = minus(nodes + 3 * t[3], p0);
  const std::array<Vec3, 3> n = {cross(e2, e3), cross(e3, e1), cross(e1, e2)};
  const double det = e1[0] * n[0][0] + e1[1] * n[0][1] + e1[2] * n[0][2];
  const double* u0 = u + 3 * t[0];
  double G[3][3] = {};  // det times the displacement gradient: G_cd = det d u_c / d p_d
  for (int k = 0; k < 3; ++k) {
    const Vec3 du = minus(u + 3 * t[k + 1], u0);
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d) G[c][d] += du[c] * n[k][d];
  }
  const double trace = m.lambda * (G[0][0] + G[1][1] + G[2][2]);
  double sigma[3][3];
  for (int c = 0; c < 3; ++c)
    for (int d = 0; d < 3; ++d) sigma[c][d] = m.mu * (G[c][d] + G[d][c]) + (c == d ? trace : 0.0);
  const double scale = 1.0 / (6.0 * det);
  double* y0 = y + 3 * t[0];
  for (int k = 0; k < 3; ++k) {
    double* yk = y + 3 * t[k + 1];
    for (int c = 0; c < 3; ++c) {
      const double f =
          scale * (sigma[c][0] * n[k][0] + sigma[c][1] * n[k][1] + sigma[c][2] * n[k][2]);
      yk[c] += f;
      y0[c] -= f;
    }
  }
}

}  // namespace

void ElementStiffness::times(const double* x, double* y, unsigned threads) const {
  sort_tetrahedra();
  const std::int64_t dofs = mesh_.dof_count();
  const auto tets = static_cast<std::int64_t>(tets_.size());
  const int asked = threads < 1 ? 1 : static_cast<int>(threads);
  copies_.resize(static_cast<std::size_t>(asked - 1) * static_cast<std::size_t>(dofs));
  const double* nodes = mesh_.nodes.data();
  int team = 1;
#pragma omp parallel num_threads(asked)
  {
    const int me = omp_get_thread_num(), size = omp_get_num_threads();
#pragma omp master
    team = size;
    double* mine = me == 0 ? y : copies_.data() + (me - 1) * dofs;
    std::fill(mine, mine + dofs, 0.0);
    for (std::int64_t e = tets * me / size; e < tets * (me + 1) / size; ++e)
      add_element(nodes, tets_[e], lame_[layer_[e]], x, mine);
  }
  for (int copy = 0; copy + 1 < team; ++copy) {
    const double* add = copies_.data() + copy * dofs;
#pragma omp parallel for num_threads(asked) schedule(static)
    for (std::int64_t k = 0; k < dofs; ++k) y[k] += add[k];
  }
}

Eigen::VectorXd ElementStiffness::diagonal() const {
  sort_tetrahedra();
  Eigen::VectorXd d = Eigen::VectorXd::Zero(mesh_.dof_count());
  for (std::size_t e = 0; e < tets_.size(); ++e) {
    const TetGradients g = tet_gradients(mesh_, tets_[e]);
    const Lame& m = lame_[layer_[e]];
    for (int a = 0; a < 4; ++a) {  // K_aa's diagonal: V ((lambda + mu) g_ac^2 + mu |g_a|^2)
      const Eigen::Vector3d ga = g.gradient.col(a);
      for (int c = 0; c < 3; ++c)
        d[3 * tets_[e][a] + c] +=
            g.volume * ((m.lambda + m.mu) * ga[c] * ga[c] + m.mu * ga.squaredNorm());
    }
  }
  return d;
}

Eigen::Matrix<double, 3, 12> ElementStiffness::element_row(std::size_t e, int a) const {
  const TetGradients g = tet_gradients(mesh_, mesh_.tets[e]);
  const Lame& m = lame_[std::min<std::size_t>(mesh_.layer[e], lame_.size() - 1)];
  const Eigen::Vector3d ga = g.gradient.col(a);
  Eigen::Matrix<double, 3, 12> row;
  for (int b = 0; b < 4; ++b) {
    const Eigen::Vector3d gb = g.gradient.col(b);
    row.middleCols<3>(3 * b) =
        g.volume * (m.lambda * ga * gb.transpose() + m.mu * gb * ga.transpose() +
                    m.mu * ga.dot(gb) * Eigen::Matrix3d::Identity());
  }
  return row;
}

void ElementStiffness::release() const {
  std::vector<Tetrahedron>().swap(tets_);
  std::vector<std::uint16_t>().swap(layer_);
  std::vector<double>().swap(copies_);
}

std::size_t ElementStiffness::bytes() const {
  return lame_.size() * sizeof(Lame) + tets_.size() * (sizeof(Tetrahedron) + 2) +
         copies_.capacity() * sizeof(double);
}

}  // namespace rumble::fem
