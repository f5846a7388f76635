// The FEM soil's static start at growing size (issue #9; the figures in
// bench/fem/MEASUREMENTS.md, "Speed and memory"): on the stiff
// example's graded hemisphere (scenarios/examples/stiff_soil_fem.json: R = 15 m, 30 sleeper
// footprints, resolution near_distance 5 m) meshed at each F_MAX, the time and iterations of
// one static solve under the sleepers' weight by each path StaticSolver has: the CHOLMOD factor
// (up to FACTOR_LIMIT DOFs) and conjugate gradients preconditioned by multigrid or by the
// diagonal. Prints one line per path
// and mesh: DOFs, setup and solve times [s], CG iterations, and the difference between paths.
//   build/release/bin/fem_static_bench [FACTOR_LIMIT] F_MAX...   (default 4e5; 50 80 120)
#include <Eigen/Core>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "boundary/absorbing_boundary.hpp"
#include "mesh/mesh_generator.hpp"
#include "operator/elasticity.hpp"
#include "settings_from_params.hpp"
#include "statics/static_solver.hpp"
#include "time/explicit_solver.hpp"

namespace {

using namespace rumble::fem;
using rumble::Footprint;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

FemSettings stiff_example(double f_max) {
  FemSettings s =
      rumble::test::soil_settings(750e6, 0.3, 1800.0);  // docs/physics.md §1.4: stiff soil
  s.mesh.radius = 15.0;
  s.mesh.f_max = f_max;
  s.mesh.near_distance = 5.0;
  return s;
}

std::vector<Footprint> sleepers() {  // 30 at 0.6 m, 2.6 m x 0.26 m, centred on x = 0
  std::vector<Footprint> fp;
  for (int i = 0; i < 30; ++i) fp.push_back({(i - 14.5) * 0.6, 0.0, 2.6, 0.26});
  return fp;
}

void run(double f_max, Eigen::Index factor_limit) {
  const FemSettings s = stiff_example(f_max);
  const std::vector<Footprint> fp = sleepers();
  const MeshPlan plan = plan_mesh(s, fp);
  auto start = std::chrono::steady_clock::now();
  const TetMesh mesh = generate_mesh(s, fp, plan);
  const double mesh_s = seconds_since(start);
  const ExplicitSolver op(
      assemble_stiffness(mesh, s), lumped_mass(mesh, s), absorbing_boundary(mesh, s, plan.region),
      true, std::vector<char>(mesh.node_count(), 0), 0.0, 0.0, 2,
      StepPrecision::kSingle);  // (the plugin's default: multigrid's fine products)
  // 1 kN down on every surface node inside a footprint: the shape of the sleepers' weight.
  Eigen::VectorXd f = Eigen::VectorXd::Zero(op.dofs());
  for (Eigen::Index node = 0; node < mesh.nodes.cols(); ++node) {
    const Eigen::Vector3d p = mesh.nodes.col(node);
    for (const Footprint& q : fp)
      if (std::abs(p.z()) < 1e-9 && std::abs(p.x() - q.x) <= 0.5 * q.width + 1e-9 &&
          std::abs(p.y() - q.y) <= 0.5 * q.length + 1e-9)
        f[3 * node + 2] += 1e3;  // N, downward (z positive downward)
  }
  std::printf("f_max %g Hz: %ld DOFs, nnz(K) %.3g, meshed in %.1f s\n", f_max,
              static_cast<long>(op.dofs()), static_cast<double>(op.stiffness().nonzeros()), mesh_s);
  Eigen::VectorXd reference;
  if (op.dofs() <= factor_limit) {
    StaticSolver factor(op.soil(), mesh.nodes);
    start = std::chrono::steady_clock::now();
    reference = factor.solve(f);
    const double first = seconds_since(start);
    start = std::chrono::steady_clock::now();
    factor.solve(f);
    std::printf("  cholmod          setup+solve %7.2f s  solve %6.3f s\n", first,
                seconds_since(start));
  }
  for (const auto& [name, kind] : {std::pair{"multigrid-cg", CgPreconditioner::kMultigrid},
                                   std::pair{"jacobi-cg", CgPreconditioner::kJacobi}}) {
    StaticSolver cg(op.soil(), mesh.nodes, 0, kind);
    start = std::chrono::steady_clock::now();
    const Eigen::VectorXd u = cg.solve(f);
    const double first = seconds_since(start);
    std::printf("  %-16s setup+solve %7.2f s  %5d iterations", name, first,
                cg.last_cg_iterations());
    if (const AmgPreconditioner* amg = cg.multigrid()) {
      std::printf("  levels");
      for (int l = 0; l < amg->levels(); ++l) std::printf(" %ld", static_cast<long>(amg->dofs(l)));
      std::printf(", operator complexity %.2f", amg->operator_complexity());
    }
    if (reference.size())
      std::printf("  |u - u_factor| / |u_factor| = %.1e",
                  (u - reference).norm() / reference.norm());
    std::printf("\n");
    std::fflush(stdout);
    // The engine's static iteration asks again with a load a little changed.
    start = std::chrono::steady_clock::now();
    cg.solve(1.01 * f);
    std::printf("  %-16s again (load +1 %%) %7.2f s  %5d iterations\n", name, seconds_since(start),
                cg.last_cg_iterations());
    std::fflush(stdout);
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<double> f_max;
  Eigen::Index limit = StaticSolver::kFactorLimit;
  int first = 1;
  if (argc > 2) limit = static_cast<Eigen::Index>(std::atof(argv[first++]));
  for (int i = first; i < argc; ++i) f_max.push_back(std::atof(argv[i]));
  if (f_max.empty()) f_max = {50, 80, 120};
  for (const double f : f_max) run(f, limit);
}
