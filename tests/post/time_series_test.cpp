// Uniform grids from recorded time columns, resampling, and reading results CSVs in the form
// engine/results/src/csv_file.cpp writes them.
#include "post/time_series.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "message_of.hpp"

namespace rumble::post {
namespace {

namespace fs = std::filesystem;

fs::path temp_file(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / "rumble_post_time_series_test" /
                       ::testing::UnitTest::GetInstance()->current_test_info()->name();
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary) << text;
  return dir / name;
}

// Times printed with 9 significant digits (as the engine's %.9g) are within 1e-8 s of the grid:
// far inside the 1 % of a step that keeps the record as it is.
TEST(UniformGrid, RoundedUniformTimesAreKept) {
  std::vector<double> t;
  for (int k = 0; k < 3000; ++k) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", 0.3 + k * 1e-4);
    t.push_back(std::stod(buf));
  }
  const UniformGrid g = uniform_grid(t, "test");
  EXPECT_FALSE(g.resampled);
  EXPECT_EQ(g.count, t.size());
  EXPECT_NEAR(g.dt, 1e-4, 1e-12);
  EXPECT_DOUBLE_EQ(g.t0, 0.3);
}

// Alternating steps (1 and 1.5 ms): resampled at the median step; linear interpolation of a
// linear function is exact, so the resampled values equal the function (to rounding, 1e-12).
TEST(UniformGrid, UnevenStepsAreInterpolatedOntoTheMedianStep) {
  std::vector<double> t = {0.0}, v;
  for (int k = 1; k < 101; ++k) t.push_back(t.back() + (k % 2 ? 1e-3 : 1.5e-3));
  for (double ti : t) v.push_back(2.0 + 3.0 * ti);
  const TimeSeries s = resample_uniform(t, v, "test");
  EXPECT_NEAR(s.dt, 1.5e-3, 1e-15);  // 50 of each: nth_element's median is the upper one
  EXPECT_EQ(s.size(), static_cast<std::size_t>(std::floor(t.back() / 1.5e-3 + 1e-9)) + 1);
  for (std::size_t k = 0; k < s.size(); ++k) EXPECT_NEAR(s.values[k], 2.0 + 3.0 * s.time(k), 1e-12);
}

TEST(UniformGrid, AGapIsRefusedWithWhereAndFix) {
  std::vector<double> t;
  for (int k = 0; k < 50; ++k) t.push_back(k * 1e-3);
  for (int k = 0; k < 50; ++k) t.push_back(0.1 + k * 1e-3);  // 51 ms gap after 49 ms
  const std::string m = message_of([&] { uniform_grid(t, "receivers.csv in 'r'"); });
  EXPECT_NE(m.find("receivers.csv in 'r'"), std::string::npos) << m;
  EXPECT_NE(m.find("varies too much"), std::string::npos) << m;
  EXPECT_NE(m.find("step of 0.051 s to data row 51 (t = 0.1 s)"), std::string::npos) << m;
  EXPECT_NE(m.find("outputs.receiver_interval"), std::string::npos) << m;
}

TEST(UniformGrid, TimeMustIncrease) {
  const std::vector<double> t = {0.0, 1e-3, 1e-3, 2e-3};
  const std::string m = message_of([&] { uniform_grid(t, "x.csv"); });
  EXPECT_NE(m.find("not strictly increasing at data row 3"), std::string::npos) << m;
  EXPECT_THROW(uniform_grid(std::vector<double>{0.0}, "x"), std::runtime_error);
}

TEST(ReadCsv, QuotedAndPlainHeaderNumbersAndNan) {
  const fs::path f = temp_file("a.csv",
                               "t [s],\"a, \"\"quoted\"\" [m/s]\",plain [m]\n"
                               "0,1.5,-2e-3\n"
                               "0.001,nan,+3\n");
  const CsvTable t = read_csv(f);
  ASSERT_EQ(t.names.size(), 2u);
  EXPECT_EQ(t.names[0], "a, \"quoted\" [m/s]");
  EXPECT_EQ(t.find("plain [m]"), std::optional<std::size_t>(1));
  EXPECT_FALSE(t.find("missing").has_value());
  ASSERT_EQ(t.time.size(), 2u);
  EXPECT_DOUBLE_EQ(t.columns[1][0], -2e-3);
  EXPECT_TRUE(std::isnan(t.columns[0][1]));
  EXPECT_DOUBLE_EQ(t.columns[1][1], 3.0);
  EXPECT_TRUE(t.warnings.empty());
}

TEST(ReadCsv, ACutLastLineIsDroppedWithAWarning) {
  const CsvTable t = read_csv(temp_file("b.csv", "t [s],v [m/s]\n0,1\n0.1,2\n0.2"));
  EXPECT_EQ(t.time.size(), 2u);
  ASSERT_EQ(t.warnings.size(), 1u);
  EXPECT_NE(t.warnings[0].find("cut last line 4"), std::string::npos);
}

TEST(ReadCsv, DamageInsideTheFileIsAnError) {
  const fs::path f = temp_file("c.csv", "t [s],v [m/s]\n0,1\n0.1\n0.2,3\n");
  const std::string m = message_of([&] { read_csv(f); });
  EXPECT_NE(m.find("c.csv:3: 1 fields, the header has 2"), std::string::npos) << m;
  const fs::path g = temp_file("d.csv", "t [s],v [m/s]\n0,abc\n0.1,2\n");
  EXPECT_NE(message_of([&] { read_csv(g); }).find("field 2 ('abc') is not a number"),
            std::string::npos);
  const fs::path h = temp_file("e.csv", "time,v\n0,1\n");
  EXPECT_NE(message_of([&] { read_csv(h); }).find("expected 't [s]'"), std::string::npos);
  EXPECT_NE(message_of([&] { read_csv(f.parent_path() / "none.csv"); }).find("cannot read"),
            std::string::npos);
}

}  // namespace
}  // namespace rumble::post
