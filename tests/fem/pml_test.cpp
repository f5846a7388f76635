// The perfectly matched layer (pml.hpp) against the viscous-spring boundary on the same box:
// a smooth vertical pulse on a footprint at the centre of the ground puts energy in; once the
// waves have crossed the box several times, what is still inside the physical box is what the
// truncation sent back. Also: a layer without damping is the elastic soil to round-off (the
// stretched operators reduce to K w), and a long run under a held load stays bounded.
#include "pml.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <vector>

#include "absorbing_boundary.hpp"
#include "elasticity.hpp"
#include "explicit_solver.hpp"
#include "footprint_loads.hpp"
#include "mesh_generator.hpp"

namespace rumble::fem {
namespace {

FemSettings box_soil(BoundaryKind kind, double margin, double pml_thickness) {
  FemSettings s;
  s.half_space = {750e6, 0.3, 1800.0};  // c_p 749, c_s 400, c_R 371 m/s
  s.mesh.shape = MeshShape::kBox;
  s.mesh.radius = margin;
  const double h = std::getenv("PML_H") ? std::atof(std::getenv("PML_H")) : 0.5;
  s.mesh.h_near = 0.5;
  s.mesh.h_max = std::getenv("PML_HMAX") ? std::atof(std::getenv("PML_HMAX")) : 1.5;
  s.mesh.near_distance = 2.0;
  (void)h;
  s.boundary.kind = kind;
  s.boundary.pml_thickness = pml_thickness;
  return s;
}

const double kMargin = std::getenv("PML_MARGIN") ? std::atof(std::getenv("PML_MARGIN")) : 8.0;
const double kShift = std::getenv("PML_ALPHA") ? std::atof(std::getenv("PML_ALPHA")) : 30.0;
struct BoxRun {
  MeshPlan plan;
  TetMesh mesh;
  FootprintWeights weights;
  std::unique_ptr<ExplicitSolver> op;
};

BoxRun make_box(const FemSettings& s, double reflection) {
  const std::vector<Footprint> fp = {{0.0, 0.0, 0.5, 0.5}};
  BoxRun r;
  r.plan = plan_mesh(s, fp);
  r.mesh = generate_mesh(s, fp, r.plan);
  r.weights = footprint_weights(r.mesh, fp);
  std::vector<BoundaryNode> boundary = absorbing_boundary(r.mesh, s, r.plan.region);
  std::vector<char> fixed(r.mesh.node_count(), 0);
  if (std::getenv("PML_FIXED") && s.boundary.kind == BoundaryKind::kPml)
    for (const BoundaryNode& b : boundary) fixed[b.node] = 1;
  r.op = std::make_unique<ExplicitSolver>(assemble_stiffness(r.mesh, s), lumped_mass(r.mesh, s),
                                          std::move(boundary), s.boundary.springs(),
                                          std::move(fixed), 0.0, 0.0, 1);
  if (s.boundary.kind == BoundaryKind::kPml)
    r.op->set_pml(PmlLayer(r.mesh, s, r.plan.physical_box(reflection, kShift)));
  return r;
}

/// Kinetic + strain energy [J] of the tetrahedra whose centroid lies in `box`.
double energy_inside(const TetMesh& m, const FemSettings& s, const PmlProfile& box,
                     const ExplicitState& st) {
  double e = 0.0;
  for (std::size_t k = 0; k < m.tets.size(); ++k) {
    const Tetrahedron& t = m.tets[k];
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (std::int32_t a : t) centroid += m.node(a) / 4.0;
    if (!box.inside_physical_box(centroid)) continue;
    const TetGradients g = tet_gradients(m, t);
    const soils::SoilProperties& p = tet_properties(m, s, k);
    Eigen::Matrix3d grad = Eigen::Matrix3d::Zero();  // d_k w_c
    for (int a = 0; a < 4; ++a) grad += g.gradient.col(a) * st.w.segment<3>(3 * t[a]).transpose();
    const Eigen::Matrix3d eps = 0.5 * (grad + grad.transpose());
    const double lambda = p.E * p.nu / ((1.0 + p.nu) * (1.0 - 2.0 * p.nu));
    e += 0.5 * g.volume * (lambda * eps.trace() * eps.trace() + 2.0 * p.shear_modulus() *
                                                                      eps.squaredNorm());
    for (int a = 0; a < 4; ++a) e += 0.125 * p.rho * g.volume * st.v.segment<3>(3 * t[a]).squaredNorm();
  }
  return e;
}

/// Energy left in the physical box (margin 8 m) at t_end over the work the pulse did (a Hann
/// pulse of 10 kN over 20 ms on a 0.5 x 0.5 m footprint; no material damping).
double energy_left(BoundaryKind kind, double margin, double pml_thickness, double t_end,
                   double reflection = 1e-3) {
  const FemSettings s = box_soil(kind, margin, pml_thickness);
  const BoxRun r = make_box(s, reflection);
  const PmlProfile physical =
      MeshPlan{.region = r.plan.region, .radius = kMargin}.physical_box(1.0, 0.0);
  ExplicitState st = r.op->rest_state();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(r.op->dofs()), w_old;
  const double duration = std::getenv("PML_PULSE") ? std::atof(std::getenv("PML_PULSE")) : 0.02;
  const double courant = std::getenv("PML_COURANT") ? std::atof(std::getenv("PML_COURANT")) : 0.8;
  const double dt = courant * r.op->stable_step(), P = 1e4;
  double work = 0.0, load_old = 0.0;
  for (double t = dt; t <= t_end; t += dt) {
    const double load = t < duration ? 0.5 * P * (1.0 - std::cos(2.0 * M_PI * t / duration)) : 0.0;
    for (const NodalWeight& w : r.weights[0]) f[3 * w.node + 2] = w.weight * load;
    w_old = st.w;
    r.op->step(st, f, dt);
    double moved = 0.0;  // area-weighted footprint displacement increment [m m^2 / m^2]
    for (const NodalWeight& w : r.weights[0]) moved += w.weight * (st.w - w_old)[3 * w.node + 2];
    work += 0.5 * (load + load_old) * moved;
    load_old = load;
    const int step = static_cast<int>(std::lround(t / dt));
    if (std::getenv("PML_TRACE") && step % static_cast<int>(0.01 / dt) == 0)
      std::printf("  t %.3f  %.3e  (dofs %ld)\n", t, energy_inside(r.mesh, s, physical, st) / work,
                  static_cast<long>(r.op->dofs()));
  }
  if (std::getenv("PML_WHERE")) {
    Eigen::Index k;
    st.v.cwiseAbs().maxCoeff(&k);
    const Eigen::Vector3d x = r.mesh.node(static_cast<std::int32_t>(k / 3));
    std::printf("largest |v| %.3e at node %ld comp %ld (%.2f, %.2f, %.2f); box %.2f..%.2f, %.2f..%.2f, depth %.2f\n",
                std::abs(st.v[k]), static_cast<long>(k / 3), static_cast<long>(k % 3), x[0], x[1], x[2],
                physical.low[0], physical.high[0], physical.low[1], physical.high[1], physical.high[2]);
  }
  return energy_inside(r.mesh, s, physical, st) / work;
}

TEST(FemPml, ALayerWithoutDampingIsTheElasticSoil) {
  // reflection 1: d0 = 0, every stretching is 1; the layer's operators reduce to K w exactly
  // (up to the order of the sums): the same run as the viscous-spring boundary on the same mesh.
  const FemSettings s = box_soil(BoundaryKind::kPml, 4.0, 2.0);
  const BoxRun a = make_box(s, 1.0);
  ASSERT_GT(a.op->pml()->tetrahedra(), 100u);
  const ExplicitSolver plain(assemble_stiffness(a.mesh, s), lumped_mass(a.mesh, s),
                             absorbing_boundary(a.mesh, s, a.plan.region), true,
                             std::vector<char>(a.mesh.node_count(), 0), 0.0, 0.0, 1);
  ExplicitState sa = a.op->rest_state(), sb = plain.rest_state();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(a.op->dofs());
  for (const NodalWeight& w : a.weights[0]) f[3 * w.node + 2] = w.weight * 1e4;
  const double dt = 0.8 * a.op->stable_step();
  for (int k = 0; k < 200; ++k) {
    a.op->step(sa, f, dt);
    plain.step(sb, f, dt);
  }
  EXPECT_LT((sa.w - sb.w).norm(), 1e-12 * sb.w.norm());
  EXPECT_LT((sa.v - sb.v).norm(), 1e-12 * sb.v.norm());
}

TEST(FemPml, TheLayerKeepsLessEnergyThanTheViscousSpringBoundary) {
  const double t_end = std::getenv("PML_END") ? std::atof(std::getenv("PML_END")) : 0.15;
  const double L = std::getenv("PML_L") ? std::atof(std::getenv("PML_L")) : 4.0;
  if (std::getenv("PML_ONLY_R")) {
    std::printf("R only: %.3e\n", energy_left(BoundaryKind::kPml, kMargin, L, t_end,
                                                std::atof(std::getenv("PML_ONLY_R"))));
    return;
  }
  const double viscous = energy_left(BoundaryKind::kViscousSpring, kMargin, 0.0, t_end);
  const double wider = energy_left(BoundaryKind::kViscousSpring, kMargin + L, 0.0, t_end);
  const double pml = energy_left(BoundaryKind::kPml, kMargin, L, t_end);
  RecordProperty("energy_left_viscous_spring_8m", std::to_string(viscous));
  RecordProperty("energy_left_viscous_spring_12m", std::to_string(wider));
  RecordProperty("energy_left_pml_8m_plus_4m", std::to_string(pml));
  std::printf("viscous 8 m %.3e, viscous 12 m %.3e, pml 8 + 4 m %.3e\n", viscous, wider, pml);
  EXPECT_LT(pml, viscous);
  for (double R : {0.5, 0.1, 1e-2, 1e-4})
    std::printf("R %.0e: %.3e\n", R, energy_left(BoundaryKind::kPml, kMargin, L, t_end, R));
}

}  // namespace
}  // namespace rumble::fem
