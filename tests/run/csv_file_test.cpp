// A results CSV row is written as printf's "%.9g" would write each value (results/csv_file.hpp):
// the tools and the tests that read the files parse that text.
#include "results/csv_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::string printf_row(double t, const std::vector<double>& values) {
  char text[64];
  std::snprintf(text, sizeof text, "%.9g", t);
  std::string row = text;
  for (double v : values) {
    std::snprintf(text, sizeof text, ",%.9g", v);
    row += text;
  }
  return row;
}

TEST(CsvFile, RowsAreWhatPrintfWrites) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("rumble_csv_file_test_" + std::to_string(::getpid()) + ".csv");
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<std::vector<double>> rows = {
      {0.0, -0.0, 1.0, -1.0, 0.1, 1e-5, -2.5e-7, 123456789.0, 1234567890.0},
      {std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::max(),
       -std::numeric_limits<double>::lowest(), 1e-300, 9.999999995e-3, 0.5e-4, 100.0, inf, -inf},
      {std::nextafter(1.0, 2.0), 1.0 / 3.0, -2.0 / 3.0, 6.02214076e23, 299792458.0, 1e16, 1e15,
       1e-4, std::nan("")}};
  {
    rumble::CsvFile file(path, {"t [s]", "a", "b", "c", "d", "e", "f", "g", "h", "i"});
    for (std::size_t r = 0; r < rows.size(); ++r) file.row(1e-3 * double(r), rows[r].data(), 9);
  }
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "t [s],a,b,c,d,e,f,g,h,i");
  for (std::size_t r = 0; r < rows.size(); ++r) {
    ASSERT_TRUE(std::getline(in, line));
    EXPECT_EQ(line, printf_row(1e-3 * double(r), rows[r])) << "row " << r;
  }
  EXPECT_FALSE(std::getline(in, line));
  std::filesystem::remove(path);
}

TEST(CsvFile, AWrongRowLengthNamesTheFile) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("rumble_csv_file_len_" + std::to_string(::getpid()) + ".csv");
  rumble::CsvFile file(path, {"t [s]", "a", "b"});
  const double v[3] = {1.0, 2.0, 3.0};
  try {
    file.row(0.0, v, 3);
    FAIL() << "a row of 3 values went into a file of 2 columns";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find(path.filename().string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("row of 3 values, header has 2"), std::string::npos);
  }
  std::filesystem::remove(path);
}

}  // namespace
