// The FEM soil's explicit step against the machine's memory bandwidth (docs/numerics.md §5): the
// step streams K's upper blocks once (4 or 8 B per value, one 4 B node index per 3 x 3 block:
// symmetric_blocks.hpp) plus its vectors, so its time is bounded below by bytes / bandwidth. Each
// case measures a STREAM-like triad in the same process first and reports the step's effective
// bandwidth as a fraction of it (roofline_fraction), with million DOF-updates per second (MDOF/s),
// per thread count.
//   build/release/bin/fem_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "boundary/absorbing_boundary.hpp"
#include "boundary/pml.hpp"
#include "mesh/kuhn_box.hpp"
#include "operator/elasticity.hpp"
#include "settings_from_params.hpp"
#include "time/explicit_solver.hpp"

namespace {

using rumble::fem::ExplicitSolver;
using rumble::fem::ExplicitState;

/// Triad a = b + s c over n doubles with `threads` threads: best bandwidth [B/s] of 20 passes,
/// counting 24 B per element (two reads, one write).
double triad_bandwidth(std::int64_t n, int threads) {
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  double best = 0.0;
  for (int pass = 0; pass < 20; ++pass) {
    const auto start = std::chrono::steady_clock::now();
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::int64_t i = 0; i < n; ++i) a[i] = b[i] + 0.5 * c[i];
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    best = std::max(best, 24.0 * static_cast<double>(n) / s);
  }
  benchmark::DoNotOptimize(a.data());
  return best;
}

/// Steps of dt [s] for as long as the benchmark asks: their wall time [s].
double timed_steps(benchmark::State& state, const ExplicitSolver& op, ExplicitState& st,
                   const Eigen::VectorXd& f, double dt) {
  const auto start = std::chrono::steady_clock::now();
  for (auto _ : state) {
    op.step(st, f, dt);
    benchmark::ClobberMemory();
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Medium soil (docs/physics.md §1.4) on a Kuhn box of n^3 cubes; LK dashpots and springs on five
/// sides, 2 % Rayleigh damping (or over 5-100 Hz by `mechanisms` Maxwell mechanisms): the step
/// the plugin takes, with K read in double (single 0) or single precision (single 1).
void BM_ExplicitStep(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const bool single = state.range(2) != 0;
  const int mechanisms = static_cast<int>(state.range(3));
  const nlohmann::json maxwell = {{"damping", {{"model", "maxwell"}, {"mechanisms", mechanisms}}}};
  const rumble::fem::FemSettings s = rumble::test::soil_settings(
      155e6, 0.3, 1800.0, mechanisms > 0 ? maxwell : nlohmann::json::object());
  const rumble::fem::TetMesh mesh = rumble::fem::kuhn_box(n, 0.164);
  const rumble::fem::TrackRegion centre{0.082 * n, 0.082 * n, 0.082 * n, 0.082 * n};
  ExplicitSolver op(
      rumble::fem::assemble_stiffness(mesh, s), rumble::fem::lumped_mass(mesh, s),
      rumble::fem::absorbing_boundary(mesh, s, centre), true,
      std::vector<char>(mesh.node_count(), 0), s.damping.mass_coefficient(),
      s.damping.stiffness_coefficient(), static_cast<unsigned>(threads),
      single ? rumble::fem::StepPrecision::kSingle : rumble::fem::StepPrecision::kDouble);
  if (mechanisms > 0) op.set_maxwell_damping(s.damping.maxwell_mechanisms());
  const Eigen::Index dofs = op.dofs();
  ExplicitState st{Eigen::VectorXd::Random(dofs) * 1e-6,
                   Eigen::VectorXd::Zero(dofs),
                   Eigen::VectorXd::Zero(dofs),
                   {},
                   {}};
  const Eigen::VectorXd f = Eigen::VectorXd::Zero(dofs);
  const double dt = 0.8 * op.stable_step();
  // K's upper blocks once (the diagonal ones and half of the others: values, a node index per
  // block, a start per node), the product's scratch read and written, w v a y read and w v a y
  // written: 10 vectors; each mechanism's memory (float) read and written.
  const auto nnz = static_cast<double>(op.stiffness().nonzeros());
  const auto nodes = static_cast<double>(dofs) / 3.0;
  const double upper_blocks = (nnz / 9.0 - nodes) / 2.0 + nodes;
  const double bytes = (single ? 4.0 : 8.0) * 9.0 * upper_blocks + 4.0 * upper_blocks +
                       8.0 * nodes + (80.0 + 8.0 * mechanisms) * static_cast<double>(dofs);
  const double bandwidth = triad_bandwidth(std::max<std::int64_t>(dofs * 8, 1 << 24), threads);
  const double seconds = timed_steps(state, op, st, f, dt);
  const double steps = static_cast<double>(state.iterations());
  state.counters["DOFs"] = static_cast<double>(dofs);
  state.counters["nnz_per_row"] = static_cast<double>(op.stiffness().nonzeros()) / dofs;
  state.counters["MDOF/s"] =
      benchmark::Counter(steps * static_cast<double>(dofs) * 1e-6, benchmark::Counter::kIsRate);
  state.counters["step_GB/s"] =
      benchmark::Counter(steps * bytes * 1e-9, benchmark::Counter::kIsRate);
  state.counters["triad_GB/s"] = bandwidth * 1e-9;
  state.counters["B_per_DOF"] = static_cast<double>(op.bytes()) / static_cast<double>(dofs);
  state.counters["roofline_fraction"] = steps * bytes / seconds / bandwidth;
}
BENCHMARK(BM_ExplicitStep)
    ->ArgNames({"n", "threads", "single", "mechanisms"})
    ->Args({20, 1, 0, 0})
    ->Args({20, 2, 0, 0})
    ->Args({32, 1, 0, 0})
    ->Args({32, 2, 0, 0})
    ->Args({46, 2, 0, 0})
    ->Args({20, 2, 1, 0})
    ->Args({32, 1, 1, 0})
    ->Args({32, 2, 1, 0})
    ->Args({46, 2, 1, 0})
    ->Args({32, 2, 1, 3})
    ->Args({46, 2, 1, 3})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// The matched layer's cost (pml.hpp): a box of 2n x 2n x n cubes (stiff soil, h 0.5 m) whose
/// outer `layer` cells are the layer (R 1e-2, fixed behind), against the same box without it
/// (layer 0: the fixed box). Reports the time per layer tetrahedron on top of the plain step.
void BM_ExplicitStepWithLayer(benchmark::State& state) {
  const int half = static_cast<int>(state.range(0)), layer = static_cast<int>(state.range(1));
  const int threads = static_cast<int>(state.range(2));
  rumble::fem::FemSettings s = rumble::test::soil_settings(750e6, 0.3, 1800.0);
  const double h = 0.5;
  const rumble::fem::TetMesh mesh =
      rumble::fem::kuhn_box(2 * half, 2 * half, half, h, -half * h, -half * h);
  std::vector<rumble::fem::BoundaryNode> boundary =
      rumble::fem::absorbing_boundary(mesh, s, rumble::fem::TrackRegion{});
  std::vector<char> fixed(mesh.node_count(), 0);
  for (const rumble::fem::BoundaryNode& b : boundary) fixed[b.node] = 1;
  ExplicitSolver op(rumble::fem::assemble_stiffness(mesh, s), rumble::fem::lumped_mass(mesh, s),
                    std::move(boundary), false, std::move(fixed), 0.0, 0.0,
                    static_cast<unsigned>(threads));
  if (layer > 0) {
    const double inner = (half - layer) * h;
    op.set_pml(rumble::fem::PmlLayer(mesh, s,
                                     {.low = {-inner, -inner, 0.0},
                                      .high = {inner, inner, inner},
                                      .thickness = layer * h,
                                      .reflection = 1e-2,
                                      .shift = 2.0 * 3.141592653589793 * 5.0}));
  }
  ExplicitState st = op.rest_state();
  st.w = Eigen::VectorXd::Random(op.dofs()) * 1e-6;
  const Eigen::VectorXd f = Eigen::VectorXd::Zero(op.dofs());
  const double dt = 0.8 * op.stable_step();
  const double seconds = timed_steps(state, op, st, f, dt);
  const double steps = static_cast<double>(state.iterations());
  const double tets = layer > 0 ? static_cast<double>(op.pml()->tetrahedra()) : 0.0;
  state.counters["DOFs"] = static_cast<double>(op.dofs());
  state.counters["layer_tets"] = tets;
  state.counters["MDOF/s"] = benchmark::Counter(steps * static_cast<double>(op.dofs()) * 1e-6,
                                                benchmark::Counter::kIsRate);
  state.counters["B_per_DOF"] = static_cast<double>(op.bytes()) / static_cast<double>(op.dofs());
  state.counters["stable_step_us"] = op.stable_step() * 1e6;
  state.counters["ms_per_step"] = seconds / steps * 1e3;
}
BENCHMARK(BM_ExplicitStepWithLayer)
    ->ArgNames({"half", "layer", "threads"})
    ->Args({16, 0, 2})
    ->Args({16, 8, 2})
    ->Args({16, 8, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// Local time stepping (local_time_stepping.hpp): the medium soil on a Kuhn box of n^3 cubes
/// (h 0.164 m, Rayleigh damping 2 %, dashpots and springs on five sides) with a stiff inclusion,
/// 4 x 4 x 2 cubes under the ground's centre with 2.5 times the modulus (c_p 1.58 times faster),
/// standing for the short elements at the footprints (the 1e6-DOF medium mesh's single-rate step
/// is 1.6 times shorter than its bulk's). local_steps 1 is one rate; the counters
/// give the stable step, the time per step and the wall time per simulated second at 0.8 of the
/// stable step, which is what local time stepping is for.
void BM_ExplicitStepLocal(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const int substeps = static_cast<int>(state.range(1));
  const int threads = static_cast<int>(state.range(2));
  constexpr double h = 0.164;
  rumble::fem::FemSettings s = rumble::test::soil_settings(155e6, 0.3, 1800.0);
  s.layers = {{1.0, rumble::soils::SoilProperties{387.5e6, 0.3, 1800.0}}};  // the inclusion
  rumble::fem::TetMesh mesh = rumble::fem::kuhn_box(n, h);
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const std::int32_t node : mesh.tets[e]) centre += mesh.node(node) / 4.0;
    const Eigen::Vector3d cell = centre / h - Eigen::Vector3d(n / 2.0, n / 2.0, 0.0);
    mesh.layer[e] = std::abs(cell.x()) < 2.0 && std::abs(cell.y()) < 2.0 && cell.z() < 2.0 ? 0 : 1;
  }
  const rumble::fem::TrackRegion centre{0.5 * h * n, 0.5 * h * n, 0.5 * h * n, 0.5 * h * n};
  ExplicitSolver op(rumble::fem::assemble_stiffness(mesh, s), rumble::fem::lumped_mass(mesh, s),
                    rumble::fem::absorbing_boundary(mesh, s, centre), true,
                    std::vector<char>(mesh.node_count(), 0), s.damping.mass_coefficient(),
                    s.damping.stiffness_coefficient(), static_cast<unsigned>(threads));
  const double single = op.stable_step();
  const rumble::fem::LocalTimeStepping* local =
      substeps > 1 && op.enable_local_steps(substeps) ? op.local_steps() : nullptr;
  ExplicitState st = op.rest_state();
  st.w = Eigen::VectorXd::Random(op.dofs()) * 1e-6;
  const Eigen::VectorXd f = Eigen::VectorXd::Zero(op.dofs());
  const double dt = 0.8 * op.stable_step();
  const double seconds = timed_steps(state, op, st, f, dt);
  const double per_step = seconds / static_cast<double>(state.iterations());
  state.counters["DOFs"] = static_cast<double>(op.dofs());
  state.counters["fine_nodes"] = local ? static_cast<double>(op.local_steps()->fine_nodes()) : 0.0;
  state.counters["halo_nodes"] = local ? static_cast<double>(op.local_steps()->halo().size()) : 0.0;
  state.counters["step_gain"] = op.stable_step() / single;
  state.counters["ms_per_step"] = per_step * 1e3;
  state.counters["wall_s_per_simulated_s"] = per_step / dt;
}
BENCHMARK(BM_ExplicitStepLocal)
    ->ArgNames({"n", "local_steps", "threads"})
    ->Args({32, 1, 2})
    ->Args({32, 2, 2})
    ->Args({32, 3, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
