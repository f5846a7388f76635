// One CsvFile row of n values (the footprint files of a 120-sleeper track have 120 values per
// row): the formatting and the flush that keeps each row on disk (results/csv_file.hpp).
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "results/csv_file.hpp"

namespace {

void BM_CsvRow(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("rumble_csv_bench_" + std::to_string(::getpid()) + ".csv");
  std::vector<std::string> columns{"t [s]"};
  for (std::size_t i = 0; i < n; ++i) columns.push_back("w" + std::to_string(i) + " [m]");
  std::vector<double> values(n);
  double t = 0.0;
  {
    rumble::CsvFile file(path, columns);
    for (auto _ : state) {
      t += 1e-3;
      for (std::size_t i = 0; i < n; ++i) values[i] = 1e-5 * std::sin(0.1 * double(i) + 40.0 * t);
      file.row(t, values.data(), n);
    }
  }
  std::filesystem::remove(path);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
}
BENCHMARK(BM_CsvRow)->Arg(8)->Arg(120)->Arg(480);

}  // namespace

BENCHMARK_MAIN();
