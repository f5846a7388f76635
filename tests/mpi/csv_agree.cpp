// Whether two results CSVs of one scenario agree to a relative tolerance, column by column: the
// same header and rows, and in each column max |a - b| <= tolerance x max |b| (a column of zeros
// in b must be zeros in a). What a run on N ranks must give against one process (issue #33:
// 1e-12, the rounding of sums taken in another order, docs/fem-soil.md "On many ranks").
// Two FEM field snapshots (.vtu, plugins/soils/fem/output/vtu_writer.cpp: the displacement and
// the velocity first in the appended data) agree when everything but those two arrays is the
// same byte for byte and each array agrees as a column does.
// usage: csv_agree A.csv B.csv TOLERANCE   (exit 0: agree; 1: differ, the worst column named;
// 2: unreadable)
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Table {
  std::string header;
  std::vector<std::vector<double>> rows;
};

bool read(const char* path, Table& t) {
  std::ifstream in(path);
  if (!in || !std::getline(in, t.header)) return false;
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    std::vector<double> row;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');)
      row.push_back(std::strtod(cell.c_str(), nullptr));
    t.rows.push_back(std::move(row));
  }
  return true;
}

std::string bytes_of(const char* path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The .vtu comparison above: returns the worst array's relative difference, or 1 for files
// whose other bytes differ.
double vtu_difference(const std::string& a, const std::string& b) {
  const std::size_t data = a.find("<AppendedData encoding=\"raw\">\n_");
  if (a.size() != b.size() || data == std::string::npos || a.compare(0, data, b, 0, data) != 0)
    return 1.0;
  std::size_t at = a.find('_', data) + 1;
  double worst = 0.0;
  for (int array = 0; array < 2; ++array) {  // displacement, velocity
    std::uint64_t size = 0;
    std::memcpy(&size, a.data() + at, sizeof size);
    if (b.compare(at, sizeof size, a, at, sizeof size) != 0) return 1.0;
    at += sizeof size;
    double scale = 0.0, difference = 0.0;
    for (std::uint64_t k = 0; k < size / 8; ++k) {
      double x = 0.0, y = 0.0;
      std::memcpy(&x, a.data() + at + 8 * k, 8);
      std::memcpy(&y, b.data() + at + 8 * k, 8);
      scale = std::max(scale, std::abs(y));
      difference = std::max(difference, std::abs(x - y));
    }
    worst = std::max(worst, scale > 0.0 ? difference / scale : (difference > 0.0 ? 1.0 : 0.0));
    at += size;
  }
  return a.compare(at, std::string::npos, b, at, std::string::npos) == 0 ? worst : 1.0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: csv_agree A.csv B.csv TOLERANCE\n");
    return 2;
  }
  Table a, b;
  const double tolerance = std::strtod(argv[3], nullptr);
  const std::string first = argv[1];
  if (first.size() > 4 && first.compare(first.size() - 4, 4, ".vtu") == 0) {
    const double worst = vtu_difference(bytes_of(argv[1]), bytes_of(argv[2]));
    std::printf("csv_agree: %s against %s: fields within %.3g\n", argv[1], argv[2], worst);
    return worst <= tolerance ? 0 : 1;
  }
  if (!read(argv[1], a) || !read(argv[2], b)) {
    std::fprintf(stderr, "csv_agree: cannot read %s or %s\n", argv[1], argv[2]);
    return 2;
  }
  if (a.header != b.header || a.rows.size() != b.rows.size() || a.rows.empty()) {
    std::printf("csv_agree: %s and %s differ in header or rows (%zu, %zu)\n", argv[1], argv[2],
                a.rows.size(), b.rows.size());
    return 1;
  }
  const std::size_t columns = b.rows.front().size();
  double worst = 0.0;
  std::size_t worst_column = 0;
  for (std::size_t c = 0; c < columns; ++c) {
    double scale = 0.0, difference = 0.0;
    for (std::size_t r = 0; r < b.rows.size(); ++r) {
      if (a.rows[r].size() != columns || b.rows[r].size() != columns) return 1;
      scale = std::max(scale, std::abs(b.rows[r][c]));
      difference = std::max(difference, std::abs(a.rows[r][c] - b.rows[r][c]));
    }
    const double relative = scale > 0.0 ? difference / scale : (difference > 0.0 ? 1.0 : 0.0);
    if (relative > worst) {
      worst = relative;
      worst_column = c;
    }
  }
  std::printf("csv_agree: %s against %s: worst column %zu within %.3g of its largest value\n",
              argv[1], argv[2], worst_column, worst);
  return worst <= tolerance ? 0 : 1;
}
