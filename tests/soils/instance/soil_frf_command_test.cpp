// `rumble soil-frf` on two scenarios, one per soil model (medium soil from properties: E = 155
// MPa, nu = 0.3, rho = 1800 kg/m^3; the 20 sleepers of small_scenario(), 2.6 x 0.26 m at 0.6 m):
// one CSV each, the driving point of the middle footprint and two transfer terms. At the lowest
// frequency (1 Hz) |H| is the static compliance: for both soils the driven footprint's is
// 1 / K_z (Gazetas; the clm keeps it by construction), the clm's transfer terms r / K_z and
// r^2 / K_z, winkler's 0. The dashpot adds (w C_z / K_z)^2 / 2 = 5e-5 at 1 Hz; the CSV has 9
// digits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../../cli/cli_runner.hpp"

namespace rumble::soiltest {
namespace {

namespace t = rumble::testing;

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
};

Csv read_csv(const std::filesystem::path& file) {
  Csv csv;
  std::ifstream in(file);
  std::string line, cell;
  for (bool first = true; std::getline(in, line); first = false) {
    std::istringstream cells(line);
    std::vector<double> row;
    while (std::getline(cells, cell, ',')) {
      if (first) {
        csv.header.push_back(cell);
      } else {
        row.push_back(std::stod(cell));
      }
    }
    if (!first) csv.rows.push_back(row);
  }
  return csv;
}

std::vector<std::string> expected_header(const std::string& label) {
  std::vector<std::string> h{"f [Hz]"};
  for (const std::string term : {"driving point", "transfer +1", "transfer +2"}) {
    h.push_back(label + " " + term + " |H| [m/N]");
    h.push_back(label + " " + term + " phase [deg]");
  }
  return h;
}

TEST(SoilFrfCommand, WritesDrivingPointAndTransferTermsForBothModels) {
  const auto dir = t::scratch_directory("soil_frf_two_models");
  const nlohmann::json medium = {{"E", 155e6}, {"nu", 0.3}, {"rho", 1800.0}};
  std::vector<std::string> files;
  for (const std::string type : {"winkler", "clm"}) {
    nlohmann::json s = t::small_scenario();
    s["soil"] = {{"type", type}, {"params", medium}};
    std::filesystem::create_directories(dir / type);
    files.push_back(t::write_scenario(dir / type, s).string());
  }
  const auto out = dir / "frf";
  const t::CliResult r =
      t::run_rumble({"soil-frf", files[0], files[1], "--output", out.string(), "--no-plot"});
  ASSERT_EQ(r.exit_code, 0) << r.output;

  // --no-plot: exactly the two CSVs, no figure (besides the directory's lock and manifest).
  std::vector<std::string> written;
  for (const auto& e : std::filesystem::directory_iterator(out))
    if (e.path().filename().string().front() != '.')
      written.push_back(e.path().filename().string());
  std::sort(written.begin(), written.end());
  EXPECT_EQ(written, (std::vector<std::string>{"scenario_clm.csv", "scenario_winkler.csv"}));

  const double G = 155e6 / 2.6, L = 1.3, B = 0.13;
  const double Kz = 2.0 * G * L / 0.7 * (0.73 + 1.54 * std::pow(B / L, 0.75));  // 2.22e8 N/m
  const Csv w = read_csv(out / "scenario_winkler.csv");
  const Csv c = read_csv(out / "scenario_clm.csv");
  EXPECT_EQ(w.header, expected_header("winkler (scenario)"));
  EXPECT_EQ(c.header, expected_header("clm (scenario)"));
  ASSERT_EQ(w.rows.size(), 100u);  // --points default
  ASSERT_EQ(c.rows.size(), 100u);
  EXPECT_EQ(w.rows.front()[0], 1.0);  // --fmin default [Hz]
  EXPECT_NEAR(w.rows.back()[0], 100.0, 1e-6);

  // Columns: f, then |H| and phase of the driving point, transfer +1, transfer +2.
  EXPECT_NEAR(w.rows.front()[1] * Kz, 1.0, 1e-4);
  EXPECT_EQ(w.rows.front()[3], 0.0);
  EXPECT_EQ(w.rows.front()[5], 0.0);
  EXPECT_NEAR(c.rows.front()[1] * Kz, 1.0, 1e-4);
  const double r1 = c.rows.front()[3] / c.rows.front()[1],
               r2 = c.rows.front()[5] / c.rows.front()[1];
  EXPECT_NEAR(r1, 0.395, 0.02 * 0.395);  // docs/physics.md §6.3
  EXPECT_NEAR(r2, r1 * r1, 1e-6);
  // A downward force moves the footprint down, later (phase in (-90, 0] degrees for a soil
  // without mass: H = 1 / (K + i w C)).
  for (const auto& row : w.rows) {
    EXPECT_LE(row[2], 0.0);
    EXPECT_GT(row[2], -90.0);
  }
}

}  // namespace
}  // namespace rumble::soiltest
