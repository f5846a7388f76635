// A study run's key (study/run_key.hpp) follows the bytes of the files that params name, at any
// depth: an edited FEM mesh file or mbs vehicle definition makes its runs run again.
#include "study/run_key.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "plugin/registry.hpp"

namespace rumble::study {
namespace {

namespace fs = std::filesystem;

class RunKeyFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::path(::testing::TempDir()) /
        ("run_key_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void write(const std::string& name, const std::string& bytes) const {
    std::ofstream(dir_ / name, std::ios::binary) << bytes;
  }
  std::string key(const nlohmann::json& scenario) const {
    const scenario::Document d{dir_ / "scenario.json", scenario.dump(), scenario};
    return run_key(PlannedRun{}, d, registry_);
  }
  fs::path dir_;
  PluginRegistry registry_;
};

TEST_F(RunKeyFiles, AFileNamedDeepInParamsIsPartOfTheKey) {
  const nlohmann::json s = {
      {"soil", {{"type", "fem"}, {"params", {{"mesh", {{"file", "soil.msh"}}}}}}}};
  write("soil.msh", "first mesh");
  const std::string first = key(s);
  EXPECT_EQ(first.size(), 64u);
  EXPECT_EQ(key(s), first);  // the same bytes, the same key
  write("soil.msh", "second mesh");
  EXPECT_NE(key(s), first);
  write("soil.msh", "first mesh");
  EXPECT_EQ(key(s), first);
  fs::remove(dir_ / "soil.msh");
  EXPECT_NE(key(s), first);  // a missing file is not the file
}

TEST_F(RunKeyFiles, AFileLargerThanOneReadIsHashedWhole) {
  const nlohmann::json s = {{"vehicles", {{{"type", "mbs"}, {"params", {{"file", "big.bin"}}}}}}};
  std::string bytes(3 * (std::size_t{1} << 20) + 17, 'a');  // three reads and a bit
  write("big.bin", bytes);
  const std::string first = key(s);
  bytes.back() = 'b';  // only the last byte of the last read differs
  write("big.bin", bytes);
  EXPECT_NE(key(s), first);
}

}  // namespace
}  // namespace rumble::study
