// The receptance cache (receptance_cache.hpp): a stored receptance reads back to the bit, another
// soil, params text, footprint weights or frequency gives another name, and a damaged or
// mismatched file is refused (the frequency is then solved again).
#include "frequency/receptance_cache.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "mesh/kuhn_box.hpp"

namespace rumble::fem {
namespace {

std::filesystem::path receptance_scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("rumble_receptance_cache_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

std::vector<std::complex<double>> some_receptance(std::size_t n) {
  std::vector<std::complex<double>> H(n * n);
  for (std::size_t k = 0; k < H.size(); ++k) H[k] = {1e-9 / (1.0 + k), -3e-10 * std::sqrt(k + 1.0)};
  return H;
}

TEST(FemReceptanceCache, StoredValuesReadBackToTheBit) {
  const auto path = receptance_scratch("a.frf");
  const auto H = some_receptance(3);
  ASSERT_TRUE(write_cached_receptance(path, 12.5, 3, H.data()));
  std::vector<std::complex<double>> back(9);
  ASSERT_TRUE(read_cached_receptance(path, 12.5, 3, back.data()));
  EXPECT_EQ(back, H);
  EXPECT_FALSE(read_cached_receptance(path, 12.5000001, 3, back.data())) << "another frequency";
  EXPECT_FALSE(read_cached_receptance(path, 12.5, 2, back.data())) << "another footprint count";
  EXPECT_FALSE(read_cached_receptance(receptance_scratch("absent.frf"), 12.5, 3, back.data()));
}

TEST(FemReceptanceCache, DamagedFilesAreRefused) {
  const auto path = receptance_scratch("b.frf");
  const auto H = some_receptance(2);
  ASSERT_TRUE(write_cached_receptance(path, 5.0, 2, H.data()));
  const auto size = std::filesystem::file_size(path);
  {  // one byte of the values flipped
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(size / 2));
    f.put('\x55');
  }
  std::vector<std::complex<double>> back(4);
  EXPECT_FALSE(read_cached_receptance(path, 5.0, 2, back.data()));
  std::filesystem::resize_file(path, size - 9);  // cut short
  EXPECT_FALSE(read_cached_receptance(path, 5.0, 2, back.data()));
}

TEST(FemReceptanceCache, NameChangesWithWhatDecidesTheReceptance) {
  const TetMesh mesh = kuhn_box(2, 0.5);
  const FootprintWeights weights = {{{0, 0.25}, {1, 0.75}}};
  const std::string params = R"({"E":1e8,"nu":0.3,"rho":1800})";
  const std::uint64_t key = receptance_soil_key(mesh, params, weights);
  EXPECT_EQ(key, receptance_soil_key(mesh, params, weights));
  const std::string name = receptance_cache_name(key, 10.0);
  EXPECT_NE(name, receptance_cache_name(key, 10.0 + 1e-12));
  EXPECT_NE(key, receptance_soil_key(mesh, R"({"E":1e8,"nu":0.3,"rho":1801})", weights));
  FootprintWeights other = weights;
  other[0][1].weight = 0.7500001;
  EXPECT_NE(key, receptance_soil_key(mesh, params, other));
  TetMesh moved = mesh;
  moved.nodes(0, 3) += 1e-9;
  EXPECT_NE(key, receptance_soil_key(moved, params, weights));
  TetMesh layered = mesh;
  layered.layer[0] = 1;
  EXPECT_NE(key, receptance_soil_key(layered, params, weights));
}

}  // namespace
}  // namespace rumble::fem
