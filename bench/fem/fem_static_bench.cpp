// The FEM soil's static start at growing size (issue #9; the figures in
// bench/fem/MEASUREMENTS.md, "Speed and memory"): on the stiff
// example's graded hemisphere (scenarios/examples/stiff_soil_fem.json: R = 15 m, 30 sleeper
// footprints, resolution near_distance 5 m) meshed at each F_MAX, the time and iterations of
// one static solve under the sleepers' weight by each path StaticSolver has: the CHOLMOD factor
// (up to FACTOR_LIMIT DOFs) and PETSc's CG with its algebraic multigrid GAMG (issue #33; the
// soil's own multigrid and CG it replaced: docs/decisions/0018-petsc-statics.md). Prints one line
// per path and mesh: DOFs, setup and solve times [s], CG iterations, and the difference from the
// factor. PATHS: a comma-separated list of gamg (StaticSolver's: CG's products by the operator's
// threaded product, K as the step reads it) and gamg-aij (by PETSc's AIJ rows, in double, on one
// thread); default both, run in that order in one process, so that a busy machine loads them
// alike; compare them by their ratios, and in both orders (the first path pays the first touch
// of fresh memory). PETSC_OPTIONS with the
// prefix fem_statics_ tunes GAMG (statics/petsc_static_solver.hpp).
//   OMP_WAIT_POLICY=passive build/release/bin/fem_static_bench [--paths=PATHS] [FACTOR_LIMIT]
//       F_MAX...   (default 4e5; 50 80 120)
#include <Eigen/Core>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "boundary/absorbing_boundary.hpp"
#include "mesh/mesh_generator.hpp"
#include "operator/elasticity.hpp"
#include "statics/static_solver.hpp"
#include "stiff_example.hpp"
#include "time/explicit_solver.hpp"

namespace {

using namespace rumble::fem;
using rumble::Footprint;
using rumble::bench::stiff_example;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// A path's solve: the solution and what the path reports after it.
struct Solved {
  Eigen::VectorXd u;
  double setup_s = 0.0;  // its set-up, within the first solve
  int iterations = 0, levels = 0;
};
using Path = std::function<Solved(const Eigen::VectorXd&)>;

/// A StaticSolver on its iterative path `kind` (built with the path, set up at its first solve).
Path static_solver(const SoilOperator& soil, const Eigen::Matrix3Xd& nodes, CgPreconditioner kind) {
  auto cg = std::make_shared<StaticSolver>(soil, nodes, 0, kind);
  return [cg](const Eigen::VectorXd& f) {
    return Solved{cg->solve(f), cg->multigrid_setup_seconds(), cg->last_cg_iterations(),
                  cg->multigrid_levels()};
  };
}

/// PETSc's GAMG with CG's products by `storage` (StaticSolver's: the step's product;
/// petsc_static_solver.hpp), set up at its first solve.
Path gamg_with(const SoilOperator& soil, const Eigen::Matrix3Xd& nodes,
               PetscStaticSolver::Storage storage) {
  auto solver = std::make_shared<std::unique_ptr<PetscStaticSolver>>();
  return [solver, &soil, &nodes, storage](const Eigen::VectorXd& f) {
    if (!*solver) *solver = std::make_unique<PetscStaticSolver>(soil, nodes, storage);
    const PetscStaticSolver& s = **solver;
    Eigen::VectorXd u = (*solver)->solve(f);
    return Solved{std::move(u), s.setup_seconds(), s.last_iterations(), s.levels()};
  };
}

/// One path's cold solve (its set-up included) and its solve again with the load changed by 1 %,
/// as the engine's static iteration asks; reference: the factor's solution, or empty.
void time_path(const char* name, const Path& path, const Eigen::VectorXd& f,
               const Eigen::VectorXd& reference) {
  auto start = std::chrono::steady_clock::now();
  const Solved first = path(f);
  const double first_s = seconds_since(start);
  std::printf("  %-14s setup %6.2f s  solve %6.2f s  %5d iterations", name, first.setup_s,
              first_s - first.setup_s, first.iterations);
  if (first.levels > 0) std::printf("  %d levels", first.levels);
  if (reference.size())
    std::printf("  |u - u_factor| / |u_factor| = %.1e",
                (first.u - reference).norm() / reference.norm());
  std::printf("\n");
  std::fflush(stdout);
  start = std::chrono::steady_clock::now();
  const Solved again = path(1.01 * f);
  std::printf("  %-14s again (load +1 %%)  solve %6.2f s  %5d iterations\n", name,
              seconds_since(start), again.iterations);
  std::fflush(stdout);
}

void run(double f_max, Eigen::Index factor_limit, const std::string& paths) {
  const FemSettings s = stiff_example(f_max);
  const std::vector<Footprint> fp = rumble::bench::stiff_example_sleepers();
  const MeshPlan plan = plan_mesh(s, fp);
  auto start = std::chrono::steady_clock::now();
  const TetMesh mesh = generate_mesh(s, fp, plan);
  const double mesh_s = seconds_since(start);
  const ExplicitSolver op(assemble_stiffness(mesh, s), lumped_mass(mesh, s),
                          absorbing_boundary(mesh, s, plan.region), true,
                          std::vector<char>(mesh.node_count(), 0), 0.0, 0.0, 2,
                          StepPrecision::kSingle);  // (the plugin's default: GAMG's CG products)
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
    std::printf("  cholmod        setup+solve %7.2f s  solve %6.3f s\n", first,
                seconds_since(start));
  }
  std::istringstream names(paths);  // (in the order given: the first pays fresh memory's faults)
  for (std::string name; std::getline(names, name, ',');) {
    if (name == "gamg-aij")
      time_path("gamg-aij", gamg_with(op.soil(), mesh.nodes, PetscStaticSolver::Storage::kAij), f,
                reference);
    if (name == "gamg")
      time_path("gamg", static_solver(op.soil(), mesh.nodes, CgPreconditioner::kGamg), f,
                reference);
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  std::string paths = "gamg,gamg-aij";
  if (!args.empty() && args.front().rfind("--paths=", 0) == 0) {
    paths = args.front().substr(8);
    args.erase(args.begin());
  }
  Eigen::Index limit = StaticSolver::kFactorLimit;
  if (args.size() > 1) {
    limit = static_cast<Eigen::Index>(std::atof(args.front().c_str()));
    args.erase(args.begin());
  }
  std::vector<double> f_max;
  for (const std::string& a : args) f_max.push_back(std::atof(a.c_str()));
  if (f_max.empty()) f_max = {50, 80, 120};
  for (const double f : f_max) run(f, limit, paths);
}
