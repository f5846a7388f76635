// The FEM soil's explicit step against the machine's two bounds (docs/fem-soil.md §4.3): the
// step streams K's upper blocks once (4 or 8 B per value, one 4 B node index per 3 x 3 block:
// symmetric_blocks.hpp) plus its vectors, so its time is bounded below by bytes / bandwidth, and
// it does 36 flops per upper block (both of its products), so also by flops / peak flops. Each
// case measures a STREAM-like triad and the peak multiply-add rate at the product's SIMD width in
// the same process first (machine_bounds.hpp) and reports both bounds per step, the step's time,
// and its fraction of whichever bound applies (bound_fraction, from the mean step;
// p10_bound_fraction from the fastest tenth of the steps, as the bounds are bests of 20 passes;
// roofline_fraction is the memory one), with million DOF-updates per second (MDOF/s), per thread
// count and kernel (simd 1: the SIMD kernel, block_kernel_avx2.hpp, where the processor has AVX2
// and FMA; simd 0: the portable one).
//   build/release/bin/fem_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include "boundary/absorbing_boundary.hpp"
#include "boundary/pml.hpp"
#include "machine_bounds.hpp"
#include "mesh/kuhn_box.hpp"
#include "mesh/mesh_generator.hpp"
#include "operator/csr_operator.hpp"
#include "operator/elasticity.hpp"
#include "settings_from_params.hpp"
#include "stiff_example.hpp"
#include "time/explicit_solver.hpp"

namespace {

using rumble::fem::ExplicitSolver;
using rumble::fem::ExplicitState;

/// Steps of dt [s] for as long as the benchmark asks: their wall time [s], and each step's in
/// `each` if given.
double timed_steps(benchmark::State& state, const ExplicitSolver& op, ExplicitState& st,
                   const Eigen::VectorXd& f, double dt, std::vector<double>* each = nullptr) {
  const auto start = std::chrono::steady_clock::now();
  auto last = start;
  for (auto _ : state) {
    op.step(st, f, dt);
    benchmark::ClobberMemory();
    if (each == nullptr) continue;
    const auto now = std::chrono::steady_clock::now();
    each->push_back(std::chrono::duration<double>(now - last).count());
    last = now;
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// What one explicit step of a mesh streams [B] and computes [flop] at least: K's upper blocks
/// once (the diagonal ones and half of the others: values, a node index per block, a start per
/// node), the product's pending sums read and written (32 B per node: NodeSum), w v a y read and
/// written (8 vectors), each mechanism's memory (float) read and written; 36 flops per upper
/// off-diagonal block (K_ij x_j and K_ij^T x_i), 18 per diagonal one, 13 per DOF for the vector
/// updates and 4 per DOF and mechanism. (Left out: the force, the mass and the node flags the
/// step also reads, about 18 B per DOF, so the memory bound is a little tight.)
struct StepCost {
  double bytes, flops;
};
StepCost step_cost(const ExplicitSolver& op, bool single, int mechanisms) {
  const auto nnz = static_cast<double>(op.stiffness().nonzeros());
  const auto dofs = static_cast<double>(op.dofs());
  const double nodes = dofs / 3.0;
  const double off_diagonal = (nnz / 9.0 - nodes) / 2.0, upper_blocks = off_diagonal + nodes;
  const double bytes = (single ? 4.0 : 8.0) * 9.0 * upper_blocks + 4.0 * upper_blocks +
                       8.0 * nodes + 64.0 * nodes + (64.0 + 8.0 * mechanisms) * dofs;
  const double flops = 36.0 * off_diagonal + 18.0 * nodes + (13.0 + 4.0 * mechanisms) * dofs;
  return {bytes, flops};
}

/// The step on `mesh` with `s` (LK dashpots and springs on its sides, away from `track`), K read
/// in double or single precision, by the SIMD kernel (where the processor has one) or the
/// portable one: its time against the machine's bounds, as counters.
void measure_step(benchmark::State& state, const rumble::fem::TetMesh& mesh,
                  const rumble::fem::FemSettings& s, const rumble::fem::TrackRegion& track,
                  int threads, bool single, bool simd) {
  const int mechanisms = s.damping.maxwell_mechanisms().mechanisms();
  auto soil = std::make_unique<rumble::fem::CsrOperator>(
      rumble::fem::assemble_stiffness(mesh, s), rumble::fem::lumped_mass(mesh, s),
      rumble::fem::absorbing_boundary(mesh, s, track), true,
      std::vector<char>(mesh.node_count(), 0), static_cast<unsigned>(threads),
      single ? rumble::fem::StepPrecision::kSingle : rumble::fem::StepPrecision::kDouble);
  soil->set_block_kernel(simd ? rumble::fem::BlockKernel::kSimd
                              : rumble::fem::BlockKernel::kPortable);
  ExplicitSolver op(std::move(soil), s.damping.mass_coefficient(),
                    s.damping.stiffness_coefficient());
  if (mechanisms > 0) op.set_maxwell_damping(s.damping.maxwell_mechanisms());
  const Eigen::Index dofs = op.dofs();
  ExplicitState st{Eigen::VectorXd::Random(dofs) * 1e-6,
                   Eigen::VectorXd::Zero(dofs),
                   Eigen::VectorXd::Zero(dofs),
                   {},
                   {}};
  const Eigen::VectorXd f = Eigen::VectorXd::Zero(dofs);
  const double dt = 0.8 * op.stable_step();
  const StepCost cost = step_cost(op, single, mechanisms);
  const double bandwidth =
      rumble::bench::triad_bandwidth(std::max<std::int64_t>(dofs * 8, 1 << 24), threads);
  const double peak = rumble::bench::peak_flops(threads);
  std::vector<double> each;  // each step's wall time [s]
  const double seconds = timed_steps(state, op, st, f, dt, &each);
  const double steps = static_cast<double>(state.iterations());
  const double memory_bound = cost.bytes / bandwidth, flop_bound = cost.flops / peak;
  // On a shared machine a step is now and then descheduled: the fastest tenth of the steps is
  // what the machine gives when it is the step's (the triad and the peak are bests too).
  std::nth_element(each.begin(), each.begin() + each.size() / 10, each.end());
  state.counters["p10_ms"] = each[each.size() / 10] * 1e3;
  state.counters["DOFs"] = static_cast<double>(dofs);
  state.counters["MDOF/s"] =
      benchmark::Counter(steps * static_cast<double>(dofs) * 1e-6, benchmark::Counter::kIsRate);
  state.counters["ms_per_step"] = seconds / steps * 1e3;
  state.counters["triad_GB/s"] = bandwidth * 1e-9;
  state.counters["peak_GFLOP/s"] = peak * 1e-9;
  state.counters["mem_bound_ms"] = memory_bound * 1e3;
  state.counters["flop_bound_ms"] = flop_bound * 1e3;
  state.counters["roofline_fraction"] = steps * memory_bound / seconds;
  state.counters["bound_fraction"] = steps * std::max(memory_bound, flop_bound) / seconds;
  state.counters["p10_bound_fraction"] =
      std::max(memory_bound, flop_bound) / each[each.size() / 10];
  state.counters["B_per_DOF"] = static_cast<double>(op.bytes()) / static_cast<double>(dofs);
}

/// Medium soil (docs/physics.md §1.4) on a Kuhn box of n^3 cubes; LK dashpots and springs on five
/// sides, 2 % Rayleigh damping (or over 5-100 Hz by `mechanisms` Maxwell mechanisms): the step
/// the plugin takes, with K read in double (single 0) or single precision (single 1), by the
/// SIMD kernel (simd 1, where the processor has one) or the portable one (simd 0). n 46 (3.1e5
/// DOFs, some 60 MB streamed a step) is issue #33's case; n 70 (1.07e6 DOFs, 200 MB) the same
/// box beyond the 32 MB L3, the size of the graded case below (bench/fem/MEASUREMENTS.md, "The
/// box beyond the L3").
void BM_ExplicitStep(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const int mechanisms = static_cast<int>(state.range(3));
  const nlohmann::json maxwell = {{"damping", {{"model", "maxwell"}, {"mechanisms", mechanisms}}}};
  const rumble::fem::FemSettings s = rumble::test::soil_settings(
      155e6, 0.3, 1800.0, mechanisms > 0 ? maxwell : nlohmann::json::object());
  const rumble::fem::TrackRegion centre{0.082 * n, 0.082 * n, 0.082 * n, 0.082 * n};
  measure_step(state, rumble::fem::kuhn_box(n, 0.164), s, centre, static_cast<int>(state.range(1)),
               state.range(2) != 0, state.range(4) != 0 && rumble::fem::block_simd_available());
}
BENCHMARK(BM_ExplicitStep)
    ->ArgNames({"n", "threads", "single", "mechanisms", "simd"})
    ->Args({20, 1, 0, 0, 1})
    ->Args({20, 2, 0, 0, 1})
    ->Args({32, 1, 0, 0, 1})
    ->Args({32, 2, 0, 0, 1})
    ->Args({46, 1, 0, 0, 1})
    ->Args({46, 2, 0, 0, 1})
    ->Args({20, 2, 1, 0, 1})
    ->Args({32, 1, 1, 0, 1})
    ->Args({32, 2, 1, 0, 1})
    ->Args({46, 1, 1, 0, 1})
    ->Args({46, 2, 1, 0, 1})
    ->Args({70, 2, 1, 0, 1})
    ->Args({32, 2, 1, 3, 1})
    ->Args({46, 2, 1, 3, 1})
    ->Args({46, 1, 0, 0, 0})
    ->Args({46, 2, 0, 0, 0})
    ->Args({46, 1, 1, 0, 0})
    ->Args({46, 2, 1, 0, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// The same step on a real mesh: the stiff example's graded gmsh hemisphere
/// (stiff_example.hpp) meshed for f_max [Hz] by HXT (215 Hz: 1.0e6 DOFs, some 15 s to mesh,
/// once per f_max), its nodes in Morton order as the plugin's. A block's node j is scattered
/// there, where a box's lie on a few strides the hardware prefetcher follows (docs/fem-soil.md
/// §4.3, "Gathers"): this is the step runs take.
void BM_ExplicitStepGraded(benchmark::State& state) {
  const double f_max = static_cast<double>(state.range(0));
  static std::map<double, rumble::fem::TetMesh> meshes;  // (one mesh per f_max for all cases)
  rumble::fem::FemSettings s = rumble::bench::stiff_example(f_max);
  s.mesh.fast_algorithm = true;
  const std::vector<rumble::Footprint> sleepers = rumble::bench::stiff_example_sleepers();
  if (meshes.count(f_max) == 0)
    meshes.emplace(f_max,
                   rumble::fem::generate_mesh(s, sleepers, rumble::fem::plan_mesh(s, sleepers)));
  measure_step(state, meshes.at(f_max), s, rumble::fem::TrackRegion::of(sleepers),
               static_cast<int>(state.range(1)), state.range(2) != 0,
               state.range(3) != 0 && rumble::fem::block_simd_available());
}
BENCHMARK(BM_ExplicitStepGraded)
    ->ArgNames({"f_max", "threads", "single", "simd"})
    ->Args({215, 1, 1, 1})
    ->Args({215, 2, 1, 1})
    ->Args({215, 2, 0, 1})
    ->Args({215, 2, 1, 0})
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
