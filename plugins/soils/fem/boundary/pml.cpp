#include "boundary/pml.hpp"

#include <cmath>

#include "operator/elasticity.hpp"
#include "wave_speeds.hpp"

namespace rumble::fem {

namespace {

// A tetrahedron's memory, 9 values each (gradient entries g_kc = d_k w_c, index 3 k + c):
constexpr int kGradient = 0;  // g at the previous step
constexpr int kPhiG = 9;      // phi g: phi' = -alpha phi + g
constexpr int kPsi = 18;      // psi: psi' = -(alpha + d_k) psi + g
constexpr int kH = 27;        // h = g - d_k psi at the previous step
constexpr int kPhiH = 36;     // phi h
constexpr int kPhi2H = 45;    // phi phi h
static_assert(kPhi2H + 9 == PmlLayer::kPerTet);

/// One trapezoidal step of the filter y' = -a y + x with the exact decay e = exp(-a dt):
/// y(t + dt) = e y(t) + dt/2 (e x(t) + x(t + dt)).
inline double filter(double y, double x_old, double x_new, double decay, double half) {
  return decay * y + half * (decay * x_old + x_new);
}

/// The stretched "stress" T_ij = lambda delta_ij sum_k X(ik)_kk + mu X(ii)_ij + mu X(ij)_ji
/// minus the elastic sigma_ij = lambda delta_ij tr g + mu (g_ij + g_ji), from the gradient g
/// (g_kc = d_k w_c at 3 k + c), A = the S / s_k^2 operator on g_kc and B(i, k, c) = the s_l
/// operator on g_kc (i != k, l the third axis): in time (the step, real) or at one frequency
/// (the receptance, complex).
template <class Scalar, class Stretch>
void stretched_minus_elastic(double lambda, double mu, const Scalar* g, const Scalar* A,
                             Stretch&& B, Scalar* T) {
  const Scalar trace = g[0] + g[4] + g[8];
  for (int i = 0; i < 3; ++i) {
    Scalar sum = A[3 * i + i];
    for (int k = 0; k < 3; ++k)
      if (k != i) sum += B(i, k, k);
    for (int j = 0; j < 3; ++j) {
      const Scalar stretched =
          (i == j ? lambda * sum + 2.0 * mu * A[3 * i + i] : mu * (A[3 * i + j] + B(i, j, i)));
      const Scalar elastic =
          (i == j ? lambda * trace : Scalar(0.0)) + mu * (g[3 * i + j] + g[3 * j + i]);
      T[3 * i + j] = stretched - elastic;
    }
  }
}

}  // namespace

PmlLayer::PmlLayer(const TetMesh& mesh, const FemSettings& settings, const PmlProfile& profile)
    : shift_(profile.shift), local_(mesh.node_count(), -1) {
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    const Tetrahedron& t = mesh.tets[e];
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (std::int32_t a : t) centroid += mesh.node(a) / 4.0;
    if (profile.inside_physical_box(centroid)) continue;
    const soils::SoilProperties& p = tet_properties(mesh, settings, e);
    const TetGradients g = tet_gradients(mesh, t);
    Tet tet{.nodes = t,
            .gradient = g.gradient,
            .volume = g.volume,
            .lambda = p.E * p.nu / ((1.0 + p.nu) * (1.0 - 2.0 * p.nu)),
            .mu = p.shear_modulus(),
            .d = profile.damping_at(centroid, soils::wave_speeds(p.E, p.nu, p.rho).pressure)};
    const double share = p.rho * g.volume / 4.0, alpha = profile.shift;
    const Eigen::Vector3d& d = tet.d;
    const double D1 = d.sum(), D2 = d[0] * d[1] + d[0] * d[2] + d[1] * d[2], D3 = d.prod();
    // u' , u, phi u, phi^2 u, phi^3 u (pml.hpp)
    const double alpha2 = alpha * alpha;
    const std::array<double, kMassTerms> terms = {
        share * D1, share * (D2 - alpha * D1), share * (alpha2 * D1 - 2.0 * alpha * D2 + D3),
        share * (alpha2 * D2 - 2.0 * alpha * D3), share * alpha2 * D3};
    for (std::int32_t a : t) {
      if (local_[a] < 0) {
        local_[a] = static_cast<std::int32_t>(mass_terms_.size());
        mass_terms_.push_back({});
      }
      for (int k = 0; k < 5; ++k) mass_terms_[local_[a]][k] += terms[k];
    }
    max_damping_ = std::max(max_damping_, tet.d.maxCoeff());
    tets_.push_back(tet);
  }
  // Incidence lists (layer node -> tetrahedron x 4 + corner), for the gather.
  incidence_offset_.assign(mass_terms_.size() + 1, 0);
  for (const Tet& t : tets_)
    for (std::int32_t a : t.nodes) ++incidence_offset_[local_[a] + 1];
  for (std::size_t k = 0; k < mass_terms_.size(); ++k)
    incidence_offset_[k + 1] += incidence_offset_[k];
  incidence_.resize(incidence_offset_.back());
  std::vector<std::int64_t> fill(incidence_offset_.begin(), incidence_offset_.end() - 1);
  for (std::size_t e = 0; e < tets_.size(); ++e)
    for (int a = 0; a < 4; ++a)
      incidence_[fill[local_[tets_[e].nodes[a]]]++] = static_cast<std::int32_t>(4 * e + a);
}

void PmlLayer::add_nodes(const std::vector<std::int32_t>& nodes) {
  for (const std::int32_t a : nodes) {
    if (local_[a] >= 0) continue;
    local_[a] = static_cast<std::int32_t>(mass_terms_.size());
    mass_terms_.push_back({});
    incidence_offset_.push_back(incidence_offset_.back());  // (none of its tetrahedra here)
  }
}

void PmlLayer::update_tetrahedra(const double* w, double dt, double* memory, double* forces) const {
  const std::int64_t count = static_cast<std::int64_t>(tets_.size());
  const double half = 0.5 * dt, decay = std::exp(-shift_ * dt);
#pragma omp single
  if (decays_dt_ != dt || decays_.size() != tets_.size()) {  // (a barrier follows: all see it)
    decays_.resize(tets_.size());
    for (std::size_t e = 0; e < tets_.size(); ++e)
      for (int k = 0; k < 3; ++k) decays_[e][k] = std::exp(-(shift_ + tets_[e].d[k]) * dt);
    decays_dt_ = dt;
  }
#pragma omp for schedule(static)
  for (std::int64_t e = 0; e < count; ++e) {
    const Tet& t = tets_[e];
    double* m = memory + kPerTet * e;
    double g[9] = {};  // g_kc = d_k w_c
    for (int a = 0; a < 4; ++a)
      for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c) g[3 * k + c] += t.gradient(k, a) * w[3 * t.nodes[a] + c];
    double A[9];  // the S / s_k^2 operator on g_kc
    for (int k = 0; k < 3; ++k) {
      const double dk = t.d[k], dl = t.d[(k + 1) % 3], dm = t.d[(k + 2) % 3];
      const double decay_k = decays_[e][k];
      for (int c = 0; c < 3; ++c) {
        const int i = 3 * k + c;
        m[kPhiG + i] = filter(m[kPhiG + i], m[kGradient + i], g[i], decay, half);
        m[kPsi + i] = filter(m[kPsi + i], m[kGradient + i], g[i], decay_k, half);
        const double h = g[i] - dk * m[kPsi + i];
        const double phi_h = filter(m[kPhiH + i], m[kH + i], h, decay, half);
        m[kPhi2H + i] = filter(m[kPhi2H + i], m[kPhiH + i], phi_h, decay, half);
        m[kPhiH + i] = phi_h;
        m[kH + i] = h;
        m[kGradient + i] = g[i];
        A[i] = h + (dl + dm) * phi_h + dl * dm * m[kPhi2H + i];
      }
    }
    // B(i, k, c): the s_l operator on g_kc for i != k, l the third axis.
    const auto B = [&](int i, int k, int c) {
      return g[3 * k + c] + t.d[3 - i - k] * m[kPhiG + 3 * k + c];
    };
    double T[9];
    stretched_minus_elastic(t.lambda, t.mu, g, A, B, T);
    double* f = forces + 12 * e;
    for (int a = 0; a < 4; ++a)
      for (int j = 0; j < 3; ++j) {
        double s = 0.0;
        for (int i = 0; i < 3; ++i) s += t.gradient(i, a) * T[3 * i + j];
        f[3 * a + j] = t.volume * s;
      }
  }
}

void PmlLayer::gather(std::int32_t local, const double* forces, double* out) const {
  for (std::int64_t k = incidence_offset_[local]; k < incidence_offset_[local + 1]; ++k) {
    const double* f = forces + 3 * static_cast<std::int64_t>(incidence_[k]);
    for (int c = 0; c < 3; ++c) out[c] += f[c];
  }
}

void PmlLayer::add_node_forces(std::int32_t local, const double* w_old, const double* w_new,
                               double dt, double* memory, double* out) const {
  const double half = 0.5 * dt, decay = std::exp(-shift_ * dt);
  const std::array<double, kMassTerms>& c = mass_terms_[local];
  double* phi = memory + kPerTet * static_cast<Eigen::Index>(tets_.size()) + kPerNode * local;
  for (int j = 0; j < 3; ++j) {
    const double phi1 = filter(phi[j], w_old[j], w_new[j], decay, half);
    const double phi2 = filter(phi[3 + j], phi[j], phi1, decay, half);
    phi[6 + j] = filter(phi[6 + j], phi[3 + j], phi2, decay, half);
    phi[j] = phi1;
    phi[3 + j] = phi2;
    out[j] += c[1] * w_new[j] + c[2] * phi1 + c[3] * phi2 + c[4] * phi[6 + j];
  }
}

void PmlLayer::frequency_domain(
    double omega,
    const std::function<void(std::int32_t, std::int32_t, const Eigen::Matrix3cd&)>& add_block,
    const std::function<void(std::int32_t, std::complex<double>)>& add_node) const {
  using Complex = std::complex<double>;
  const Complex q = 1.0 / Complex(shift_, omega), iw(0.0, omega);
  for (const Tet& t : tets_) {
    // s_k = 1 + d_k q; the operators of update_tetrahedra: A = s_l s_m / s_k on g_kc (k's two
    // other axes l, m), B = s_l on g_kc in T_ij (i != k, l the third axis).
    Complex stretch[3];
    for (int k = 0; k < 3; ++k) stretch[k] = 1.0 + t.d[k] * q;
    // The correction's column for each unit displacement (b, c): T_ij as the step forms it
    // (stretched_minus_elastic), then the force V sum_i dN_a/dx_i T_ij.
    Eigen::Matrix<Complex, 12, 12> block = Eigen::Matrix<Complex, 12, 12>::Zero();
    for (int b = 0; b < 4; ++b)
      for (int c = 0; c < 3; ++c) {
        Complex g[9] = {};  // g_kc = dN_b/dx_k for component c
        for (int k = 0; k < 3; ++k) g[3 * k + c] = t.gradient(k, b);
        Complex A[9];
        for (int k = 0; k < 3; ++k)
          for (int e = 0; e < 3; ++e)
            A[3 * k + e] = stretch[(k + 1) % 3] * stretch[(k + 2) % 3] / stretch[k] * g[3 * k + e];
        const auto B = [&](int i, int k, int e) { return stretch[3 - i - k] * g[3 * k + e]; };
        Complex T[9];
        stretched_minus_elastic(t.lambda, t.mu, g, A, B, T);
        for (int a = 0; a < 4; ++a)
          for (int j = 0; j < 3; ++j) {
            Complex f = 0.0;
            for (int i = 0; i < 3; ++i) f += t.gradient(i, a) * T[3 * i + j];
            block(3 * a + j, 3 * b + c) = t.volume * f;
          }
      }
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        add_block(t.nodes[a], t.nodes[b], block.block<3, 3>(3 * a, 3 * b));
  }
  // The mass side: c0 u' + c1 u + c2 phi u + c3 phi^2 u + c4 phi^3 u (add_node_forces).
  for (std::size_t node = 0; node < local_.size(); ++node) {
    if (local_[node] < 0) continue;
    const std::array<double, kMassTerms>& c = mass_terms_[local_[node]];
    add_node(static_cast<std::int32_t>(node),
             iw * c[0] + c[1] + c[2] * q + c[3] * q * q + c[4] * q * q * q);
  }
}

std::size_t PmlLayer::bytes() const {
  // Geometry and forces per tetrahedron, mass terms and incidence offsets per node, and the
  // memory variables the state holds for it (ExplicitState::pml).
  return tets_.size() * (sizeof(Tet) + 12 * 8 + 3 * 8) + local_.size() * 4 +
         mass_terms_.size() * (40 + 8) + incidence_.size() * 4 +
         static_cast<std::size_t>(memory_size()) * 8;
}

}  // namespace rumble::fem
