// The parameter tables of docs/soils.md, recomputed through the plugins: winkler's k, c, m and
// the clm's m_f, k_f, c_f, k_c, c_c for the three soils of docs/physics.md §1.4 (E = 10, 155, 750
// MPa, nu = 0.3, rho = 1800 kg/m^3) under 2.6 x 0.26 m sleepers at 0.6 m. Every table row whose
// first cell is soft, medium or stiff is read; each column whose header names one of those
// quantities must agree to half a unit of the last digit written. Every quantity of every soil
// must be found, so the test fails when the documentation drifts from the plugins or loses a
// number. The values are read back through the receptance (soil_rig's lumped_parameters).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "soil_rig.hpp"

namespace rumble::soiltest {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" `*"), e = s.find_last_not_of(" `*");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line.substr(1));  // after the leading '|'
  std::string cell;
  while (std::getline(in, cell, '|')) out.push_back(trim(cell));
  return out;
}

/// Half a unit of the last digit of a number written as "1.434e7", "8.70e4", "0", "90.3".
double last_digit_half_unit(const std::string& text) {
  const auto e = text.find_first_of("eE");
  const std::string mantissa = text.substr(0, e);
  const auto dot = mantissa.find('.');
  const int decimals = dot == std::string::npos ? 0 : static_cast<int>(mantissa.size() - dot - 1);
  const int exponent = e == std::string::npos ? 0 : std::stoi(text.substr(e + 1));
  return 0.5 * std::pow(10.0, exponent - decimals);
}

/// Which quantity a column holds, from its header cell ("" when none of ours): the symbol,
/// optionally followed by its unit in brackets ("K_z [N/m]", "m_f", "mass").
std::string quantity(const std::string& header, bool clm_table) {
  const std::string name = header.substr(0, header.find(' '));
  const std::string rest = header.substr(name.size());
  if (!rest.empty() && trim(rest).front() != '[') return "";  // "C_z / K_z [ms]" is another one
  if (name == "K_z" || name == "k") return "winkler k";
  if (name == "C_z" || name == "c") return "winkler c";
  if (name == "mass" || name == "m") return clm_table ? "clm m_f" : "winkler m";
  for (const char* p : {"m_f", "k_f", "c_f", "k_c", "c_c"})
    if (name == p) return std::string("clm ") + p;
  return "";
}

TEST(SoilDocsTable, ParameterTablesMatchThePlugins) {
  std::map<std::string, std::map<std::string, double>> computed;  // soil -> quantity -> value
  const std::map<std::string, double> moduli = {
      {"soft", 10e6}, {"medium", 155e6}, {"stiff", 750e6}};
  for (const auto& [soil, E] : moduli) {
    auto winkler = make_soil("winkler", soil_properties(E), sleeper_row(3));
    const Lumped w = lumped_parameters(*winkler, 3);
    auto clm = make_soil("clm", soil_properties(E), sleeper_row(9));
    const Lumped c = lumped_parameters(*clm, 9);
    computed[soil] = {{"winkler k", w.k_f}, {"winkler c", w.c_f}, {"winkler m", w.m_f},
                      {"clm m_f", c.m_f},   {"clm k_f", c.k_f},   {"clm c_f", c.c_f},
                      {"clm k_c", c.k_c},   {"clm c_c", c.c_c}};
    std::printf(
        "  %-6s winkler k %.4e N/m, c %.4e N s/m, m %.1f kg | clm m_f %.1f kg, k_f %.4e "
        "N/m, c_f %.4e N s/m, k_c %.4e N/m, c_c %.4e N s/m\n",
        soil.c_str(), w.k_f, w.c_f, w.m_f, c.m_f, c.k_f, c.c_f, c.k_c, c.c_c);
  }

  std::ifstream doc(std::string(RUMBLE_TEST_SOURCE_DIR) + "/docs/soils.md");
  ASSERT_TRUE(doc) << "docs/soils.md not found";
  std::set<std::string> checked;  // "soil quantity"
  std::vector<std::string> header;
  std::string line;
  for (int number = 1; std::getline(doc, line); ++number) {
    if (line.empty() || line[0] != '|') {
      header.clear();
      continue;
    }
    const std::vector<std::string> row = cells(line);
    if (header.empty()) {
      header = row;
      continue;
    }
    if (row.empty() || !moduli.contains(row[0])) continue;
    const bool clm_table = std::find_if(header.begin(), header.end(), [](const std::string& h) {
                             return h.rfind("k_f", 0) == 0;
                           }) != header.end();
    for (std::size_t j = 1; j < row.size() && j < header.size(); ++j) {
      const std::string q = quantity(header[j], clm_table);
      if (q.empty()) continue;
      const double written = std::stod(row[j]), value = computed[row[0]][q];
      EXPECT_NEAR(value, written, last_digit_half_unit(row[j]))
          << "docs/soils.md:" << number << ": " << row[0] << " " << q << " is written " << row[j];
      checked.insert(row[0] + " " + q);
    }
  }
  for (const auto& [soil, values] : computed) {
    for (const auto& [q, v] : values) {
      EXPECT_TRUE(checked.contains(soil + " " + q))
          << "docs/soils.md gives no " << q << " for the " << soil << " soil (" << v << ")";
    }
  }
}

}  // namespace
}  // namespace rumble::soiltest
