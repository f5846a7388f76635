// K x in double two ways (issue #33, docs/fem-soil.md §8, "K without its rows"): from K's
// assembled rows (CSR: 12 B per nonzero streamed, about 540 B per DOF) and element by element
// from the mesh (operator/element_stiffness.hpp: the nodes' positions, 24 B per node, and its
// sorted copy of the tetrahedra, 18 B each; about 200 flops per tetrahedron). The rows' product
// is bound by memory (the triad measured in the same process, machine_bounds.hpp, and the rows'
// bound reported); the elements' is reported in ns per tetrahedron and as a ratio to the rows'
// time on the same mesh and threads, the figure that says what freeing the rows costs the
// statics on the ranks (one double product per CG iteration there).
//   build/release/bin/fem_bench --benchmark_counters_tabular=true
//       --benchmark_filter=BM_StiffnessProduct   (one command line)
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <chrono>
#include <map>

#include "machine_bounds.hpp"
#include "mesh/kuhn_box.hpp"
#include "mesh/mesh_generator.hpp"
#include "operator/element_stiffness.hpp"
#include "settings_from_params.hpp"
#include "stiff_example.hpp"

namespace {

/// Seconds per product of `product` over `state`'s iterations.
template <class Product>
double seconds_per_product(benchmark::State& state, Product&& product) {
  const auto start = std::chrono::steady_clock::now();
  for (auto _ : state) {
    product();
    benchmark::ClobberMemory();
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
         static_cast<double>(state.iterations());
}

/// form 0: the rows (CSR, rows split over the threads); 1: the elements.
void measure_product(benchmark::State& state, const rumble::fem::TetMesh& mesh,
                     const rumble::fem::FemSettings& s, bool elements, int threads) {
  // (per mesh: the rows case just before, on as many threads, by the cases' order below)
  static std::map<const rumble::fem::TetMesh*, double> rows_seconds;
  const rumble::fem::CsrMatrix K = rumble::fem::assemble_stiffness(mesh, s);
  const rumble::fem::ElementStiffness formed(mesh, s);
  const Eigen::VectorXd x = Eigen::VectorXd::Random(mesh.dof_count());
  Eigen::VectorXd y(mesh.dof_count());
  const std::int64_t rows = K.rows();
  const double seconds = seconds_per_product(state, [&] {
    if (elements) {
      formed.times(x.data(), y.data(), static_cast<unsigned>(threads));
      return;
    }
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::int64_t i = 0; i < rows / 3; ++i)
      K.node_rows_dot(static_cast<std::int32_t>(i), x.data(), y.data() + 3 * i);
  });
  benchmark::DoNotOptimize(y.data());
  const double dofs = static_cast<double>(mesh.dof_count());
  const double rows_bytes = 12.0 * static_cast<double>(K.nonzeros()) + 16.0 * dofs;
  const double bandwidth = rumble::bench::triad_bandwidth(
      std::max<std::int64_t>(mesh.dof_count() * 8, 1 << 24), threads);
  if (!elements) rows_seconds[&mesh] = seconds;
  state.counters["DOFs"] = dofs;
  state.counters["ms_per_product"] = seconds * 1e3;
  state.counters["ns_per_tet"] = seconds * 1e9 / static_cast<double>(mesh.tets.size());
  state.counters["triad_GB/s"] = bandwidth * 1e-9;
  state.counters["rows_mem_bound_ms"] = rows_bytes / bandwidth * 1e3;
  if (elements && rows_seconds.count(&mesh) != 0)
    state.counters["over_rows"] = seconds / rows_seconds.at(&mesh);
}

/// Each mesh's cases: the rows, then the elements, on one thread and on two (the elements' ratio
/// is taken to the rows' case just before).
void product_cases(benchmark::internal::Benchmark* b) {
  b->ArgNames({"elements", "threads"})->Args({0, 1})->Args({1, 1})->Args({0, 2})->Args({1, 2});
}

/// Medium soil on a Kuhn box of n^3 cubes of 0.164 m (46: 3.1e5 DOFs, as BM_ExplicitStep).
void BM_StiffnessProductBox(benchmark::State& state) {
  static const rumble::fem::TetMesh box = rumble::fem::kuhn_box(46, 0.164);
  measure_product(state, box, rumble::test::soil_settings(155e6, 0.3, 1800.0), state.range(0) != 0,
                  static_cast<int>(state.range(1)));
}
BENCHMARK(BM_StiffnessProductBox)
    ->Apply(product_cases)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// The stiff example's graded gmsh hemisphere for 215 Hz (1.0e6 DOFs, stiff_example.hpp), its
/// nodes in the plugin's Morton order: a tetrahedron's nodes scattered, as in runs.
void BM_StiffnessProductGraded(benchmark::State& state) {
  rumble::fem::FemSettings s = rumble::bench::stiff_example(215.0);
  s.mesh.fast_algorithm = true;
  static const rumble::fem::TetMesh mesh = [&s] {
    const auto sleepers = rumble::bench::stiff_example_sleepers();
    return rumble::fem::generate_mesh(s, sleepers, rumble::fem::plan_mesh(s, sleepers));
  }();
  measure_product(state, mesh, s, state.range(0) != 0, static_cast<int>(state.range(1)));
}
BENCHMARK(BM_StiffnessProductGraded)
    ->Apply(product_cases)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
