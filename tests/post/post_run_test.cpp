// post_process on small results directories written by the test, in both receivers.csv forms:
// the files appear with the expected numbers (closed forms of the synthetic signals), and a
// missing file or column gives a message with what, where and the fix.
#include "post/post_run.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "message_of.hpp"
#include "post/din4150.hpp"
#include "post/time_series.hpp"

namespace rumble::post {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kRunDt = 1e-3;   // s
constexpr std::size_t kN = 2000;  // 2 s
constexpr double kA = 2e-3;       // m/s

fs::path fresh_dir() {
  const fs::path dir = fs::temp_directory_path() / "rumble_post_run_test" /
                       ::testing::UnitTest::GetInstance()->current_test_info()->name();
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void expect_contains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "'" << part << "' not in: " << text;
}

// A receivers.csv as the engine writes it: header, then %.9g numbers.
void write_csv(const fs::path& file, const std::vector<std::string>& names,
               const std::vector<std::vector<double>>& columns) {
  std::ofstream out(file);
  out << "t [s]";
  for (const std::string& n : names) out << "," << n;
  out << "\n";
  for (std::size_t k = 0; k < columns.front().size(); ++k) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(k) * kRunDt);
    out << buf;
    for (const auto& c : columns) {
      std::snprintf(buf, sizeof buf, "%.9g", c[k]);
      out << "," << buf;
    }
    out << "\n";
  }
}

std::vector<double> sine_at_fs(double a, double f) {
  std::vector<double> v(kN);
  for (std::size_t k = 0; k < kN; ++k)
    v[k] = a * std::sin(2.0 * std::numbers::pi * f * static_cast<double>(k) * kRunDt);
  return v;
}

// A CSV file as rows of name -> field.
std::vector<std::map<std::string, std::string>> read_rows(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split_csv_line(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> f = split_csv_line(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < f.size(); ++i) row[header[i]] = f[i];
    rows.push_back(row);
  }
  return rows;
}

double number(const std::map<std::string, std::string>& row, const std::string& key) {
  const auto it = row.find(key);
  if (it == row.end()) throw std::out_of_range("no column '" + key + "'");
  return std::stod(it->second);
}

// Probe receivers: "d=2.5 m" moves along a fixed direction (vx = 0.6 s(t), vz = 0.8 s(t),
// s = A sin(2 pi 25 t): the 25 Hz crests fall on samples), "d=5 m" vertically at 10 Hz with A/4,
// "deep" (distance from summary.json only) at 2.5 m and 1 m depth.
fs::path probe_run() {
  const fs::path dir = fresh_dir();
  const std::vector<double> s25 = sine_at_fs(kA, 25.0), s10 = sine_at_fs(kA / 4, 10.0),
                            zero(kN, 0.0);
  std::vector<double> vx(kN), vz(kN);
  for (std::size_t k = 0; k < kN; ++k) vx[k] = 0.6 * s25[k], vz[k] = 0.8 * s25[k];
  std::vector<std::string> names;
  std::vector<std::vector<double>> cols;
  auto add = [&](const std::string& n, const std::vector<double>& x, const std::vector<double>& y,
                 const std::vector<double>& z) {
    for (const char* c : {"vx [m/s]", "vy [m/s]", "vz [m/s]", "ux [m]", "uy [m]", "uz [m]"})
      names.push_back(n + " " + c);
    for (const auto* v : {&x, &y, &z, &zero, &zero, &zero}) cols.push_back(*v);
  };
  add("d=2.5 m", vx, zero, vz);
  add("d=5 m", zero, zero, s10);
  add("deep", zero, zero, s10);
  write_csv(dir / "receivers.csv", names, cols);
  const json summary = {
      {"ppv",
       {{{"name", "d=2.5 m"}, {"x_m", 24.0}, {"distance_m", 2.5}, {"depth_m", 0.0}},
        {{"name", "d=5 m"}, {"x_m", 24.0}, {"distance_m", 5.0}, {"depth_m", 0.0}},
        {{"name", "deep"}, {"x_m", 24.0}, {"distance_m", 2.5}, {"depth_m", 1.0}}}}};
  std::ofstream(dir / "summary.json") << summary.dump(2);
  return dir;
}

// The numbers come from %.9g CSV values of exactly sampled sines: PPV and spectra to 1e-8
// relative; KB_F,max is the steady-sine closed form (din4150.hpp) to 0.1 % (after 2 s the Fast
// average has settled to exp(-16): the remaining error is the filter's, <= 1e-4, see
// din4150_test); the band level of a bin-centred sine is exact (1e-6 dB for the CSV rounding);
// the CWT at a grid frequency equal to the tone's gives A to 0.1 % at the record's middle.
TEST(PostRun, ProbeReceiversGiveTheClosedFormNumbers) {
  const fs::path dir = probe_run();
  PostOptions options;
  options.cwt_f_min = 6.25, options.cwt_f_max = 100.0, options.cwt_n_freq = 5;  // 25 Hz is one
  options.cwt_max_times = 500;
  const PostResult r = post_process(dir, options);
  for (const char* f : {"ppv.csv", "spectra.csv", "third_octave.csv", "cwt_d=2.5_m.csv",
                        "cwt_d=5_m.csv", "post.json"})
    EXPECT_TRUE(fs::exists(dir / "post" / f)) << f;
  EXPECT_FALSE(fs::exists(dir / "post" / "cwt_deep.csv"));  // the surface one at 2.5 m wins
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();

  const auto ppv = read_rows(dir / "post" / "ppv.csv");
  ASSERT_EQ(ppv.size(), 3u);
  EXPECT_EQ(ppv[0].at("receiver"), "d=2.5 m");  // by distance, then depth
  EXPECT_EQ(ppv[1].at("receiver"), "deep");
  EXPECT_EQ(ppv[2].at("receiver"), "d=5 m");
  const auto& near = ppv[0];
  EXPECT_NEAR(number(near, "distance [m]"), 2.5, 1e-12);
  EXPECT_NEAR(number(near, "x [m]"), 24.0, 1e-12);
  EXPECT_NEAR(number(near, "PPV_z [m/s]"), 0.8 * kA, 1e-8 * kA);
  EXPECT_NEAR(number(near, "PPV_3c [m/s]"), kA, 1e-8 * kA);
  EXPECT_NEAR(number(near, "t(PPV_z) [s]"), 0.01, 1e-12);  // first crest
  EXPECT_EQ(near.at("component"), "vz");
  EXPECT_NEAR(number(near, "f_dom [Hz]"), 25.0, 1e-9);
  const double ripple =
      std::sqrt(1.0 + 1.0 / std::hypot(1.0, 4.0 * std::numbers::pi * 25.0 * kFastTau));
  EXPECT_NEAR(number(near, "KB_F,max [m/s]"), 0.8 * kA / std::sqrt(2.0) * kb_gain(25.0) * ripple,
              1e-3 * kA);
  EXPECT_NEAR(number(near, "v_eff,F,max [m/s]"), 0.8 * kA / std::sqrt(2.0) * ripple, 1e-3 * kA);
  EXPECT_NEAR(number(near, "v_rms_z [m/s]"), 0.8 * kA / std::sqrt(2.0), 1e-8 * kA);
  // DIN 4150-3 line 2 at 25 Hz: 5 + 10 (25 - 10) / 40 = 8.75 mm/s; BS 7385-2 line 2: 20 + 1.2 * 10.
  EXPECT_NEAR(number(near, "DIN 4150-3 line 2 [m/s]"), 8.75e-3, 1e-12);
  EXPECT_NEAR(number(near, "PPV / DIN 4150-3 line 2 [-]"), 0.8 * kA / 8.75e-3, 1e-8);
  EXPECT_NEAR(number(near, "BS 7385-2 line 2 [m/s]"), 32e-3, 1e-12);
  EXPECT_NEAR(number(near, "PPV / BS 7385-2 line 1 [-]"), 0.8 * kA / 50e-3, 1e-8);
  EXPECT_NEAR(number(ppv[2], "PPV_z [m/s]"), kA / 4, 1e-8 * kA);
  EXPECT_NEAR(number(ppv[2], "f_dom [Hz]"), 10.0, 1e-9);

  // spectra.csv: the Hann amplitude at 25 Hz (bin 50 of 2 s) is the component's amplitude.
  const auto spectra = read_rows(dir / "post" / "spectra.csv");
  ASSERT_GT(spectra.size(), 50u);
  EXPECT_NEAR(number(spectra[50], "f [Hz]"), 25.0, 1e-12);
  EXPECT_NEAR(number(spectra[50], "d=2.5 m vz [m/s]"), 0.8 * kA, 1e-8 * kA);
  EXPECT_NEAR(number(spectra[50], "d=2.5 m vx [m/s]"), 0.6 * kA, 1e-8 * kA);
  EXPECT_NEAR(number(spectra.back(), "f [Hz]"), 500.0, 1e-12);  // up to Nyquist, <= 500 Hz

  // third_octave.csv: the 25 Hz band holds the tone.
  const auto bands = read_rows(dir / "post" / "third_octave.csv");
  const std::string col = "d=2.5 m vz L_v [dB re 1e-09 m/s]";
  bool found = false;
  for (const auto& b : bands)
    if (b.at("band [Hz]") == "25") {
      found = true;
      EXPECT_NEAR(number(b, col), 20.0 * std::log10(0.8 * kA / std::sqrt(2.0) / 1e-9), 1e-6);
    }
  EXPECT_TRUE(found);

  // cwt_d=2.5_m.csv: every 4th sample (2000 / 500), |W| at 25 Hz in the middle is 0.8 A.
  const auto cwt = read_rows(dir / "post" / "cwt_d=2.5_m.csv");
  ASSERT_EQ(cwt.size(), 500u);
  EXPECT_NEAR(number(cwt[250], "t [s]"), 1.0, 1e-12);
  EXPECT_NEAR(number(cwt[250], "|W| 25 Hz [m/s]"), 0.8 * kA, 1e-3 * kA);
  EXPECT_LT(number(cwt[250], "f_coi [Hz]"), 6.25);

  // post.json carries the same numbers.
  const json report = json::parse(std::ifstream(dir / "post" / "post.json"));
  EXPECT_EQ(report["source"]["form"], "probes");
  EXPECT_DOUBLE_EQ(report["sampling"]["dt_s"].get<double>(), kRunDt);
  EXPECT_EQ(report["sampling"]["samples"], kN);
  const json& rx = report["receivers"][0];
  EXPECT_EQ(rx["name"], "d=2.5 m");
  EXPECT_NEAR(rx["ppv_z_m_s"].get<double>(), number(near, "PPV_z [m/s]"), 1e-9 * kA);
  EXPECT_NEAR(rx["ppv_3c_m_s"].get<double>(), kA, 1e-8 * kA);
  EXPECT_NEAR(rx["din4150_3"][1]["guide_m_s"].get<double>(), 8.75e-3, 1e-12);
  EXPECT_NEAR(rx["components"]["vx"]["ppv_m_s"].get<double>(), 0.6 * kA, 1e-8 * kA);
  EXPECT_EQ(report["cwt"].size(), 2u);
  EXPECT_EQ(report["cwt"][0]["receiver"], "d=2.5 m");
  EXPECT_EQ(report["cwt"][1]["receiver"], "d=5 m");
}

// Within the resolved band every indicator of the low-passed record stands beside the raw one
// (issue #29 item 1): a 25 Hz tone under a band of 100 Hz keeps its KB_F,max, dominant frequency
// and guide ratios (the zero-phase 4th-order low-pass passes 25 Hz with |H|^2 = 1 / (1 + 0.25^8),
// 1.5e-5 off); a 10 Hz tone under a band of 2 Hz has little left (|H|^2 = 2.6e-6 at 10 Hz); a
// receiver whose soil says no band has none (NaN, null).
TEST(PostRun, TheResolvedBandGivesEveryIndicatorOfTheLowPassedRecord) {
  const fs::path dir = probe_run();
  json summary = json::parse(std::ifstream(dir / "summary.json"));
  summary["ppv"][0]["resolved_f_hz"] = 100.0;
  summary["ppv"][1]["resolved_f_hz"] = 2.0;
  std::ofstream(dir / "summary.json") << summary.dump(2);
  post_process(dir);
  const auto ppv = read_rows(dir / "post" / "ppv.csv");
  ASSERT_EQ(ppv.size(), 3u);
  const auto& near = ppv[0];  // 25 Hz, band 100 Hz
  EXPECT_NEAR(number(near, "KB_F,max resolved [m/s]"), number(near, "KB_F,max [m/s]"), 1e-3 * kA);
  EXPECT_NEAR(number(near, "f_dom resolved [Hz]"), 25.0, 0.5);
  EXPECT_NEAR(number(near, "PPV / DIN 4150-3 line 2 resolved [-]"),
              number(near, "PPV / DIN 4150-3 line 2 [-]"), 2e-3);
  EXPECT_NEAR(number(near, "PPV / BS 7385-2 line 1 resolved [-]"),
              number(near, "PPV / BS 7385-2 line 1 [-]"), 2e-3);
  const auto& far = ppv[2];  // 10 Hz, band 2 Hz
  EXPECT_EQ(far.at("receiver"), "d=5 m");
  // What is left is the record's abrupt start and end, which reach below 2 Hz (measured 0.037).
  EXPECT_LT(number(far, "KB_F,max resolved [m/s]"), 0.1 * number(far, "KB_F,max [m/s]"));
  EXPECT_EQ(ppv[1].at("receiver"), "deep");
  EXPECT_TRUE(std::isnan(number(ppv[1], "KB_F,max resolved [m/s]")));
  const json report = json::parse(std::ifstream(dir / "post" / "post.json"));
  const json& band = report["receivers"][0]["resolved_band"];
  EXPECT_NEAR(band["kb_f_max_m_s"].get<double>(), number(near, "KB_F,max resolved [m/s]"),
              1e-9 * kA);
  EXPECT_NEAR(band["din4150_3_ratios"][1].get<double>(),
              number(near, "PPV / DIN 4150-3 line 2 resolved [-]"), 1e-9);
  EXPECT_TRUE(report["receivers"][1]["resolved_band"]["kb_f_max_m_s"].is_null());
}

// The warning about energy above the band judges the PPV by what the band keeps of it (not by the
// share of energy): a 5 Hz tone with a 50 Hz one of 0.6 its amplitude under a band of 20 Hz has
// 26.5 % of its energy above the band (0.36 / 1.36), but the band keeps 0.63 of its PPV (A
// against 1.588 A, the largest sample of the two); a 10 Hz tone under a band of 2 Hz keeps almost
// none: its PPV is the mesh's.
TEST(PostRun, TheBandWarningSaysHowMuchOfThePpvTheBandKeeps) {
  const fs::path dir = fresh_dir();
  const std::vector<double> s5 = sine_at_fs(kA, 5.0), s50 = sine_at_fs(0.6 * kA, 50.0),
                            s10 = sine_at_fs(kA, 10.0), zero(kN, 0.0);
  using Probe = std::pair<const char*, const std::vector<double>*>;
  std::vector<double> two_tones(kN);
  for (std::size_t k = 0; k < kN; ++k) two_tones[k] = s5[k] + s50[k];
  std::vector<std::string> names;
  std::vector<std::vector<double>> cols;
  for (const auto& [name, vz] : {Probe{"near", &two_tones}, Probe{"far", &s10}}) {
    for (const char* c : {"vx [m/s]", "vy [m/s]", "vz [m/s]", "ux [m]", "uy [m]", "uz [m]"})
      names.push_back(std::string(name) + " " + c);
    for (const std::vector<double>* v : {&zero, &zero, vz, &zero, &zero, &zero}) cols.push_back(*v);
  }
  write_csv(dir / "receivers.csv", names, cols);
  const json summary = {{"ppv",
                         {{{"name", "near"},
                           {"x_m", 24.0},
                           {"distance_m", 2.5},
                           {"depth_m", 0.0},
                           {"resolved_f_hz", 20.0}},
                          {{"name", "far"},
                           {"x_m", 24.0},
                           {"distance_m", 5.0},
                           {"depth_m", 0.0},
                           {"resolved_f_hz", 2.0}}}}};
  std::ofstream(dir / "summary.json") << summary.dump(2);
  const PostResult r = post_process(dir);
  ASSERT_EQ(r.warnings.size(), 2u) << ::testing::PrintToString(r.warnings);
  expect_contains(r.warnings[0],
                  "receiver 'near': 26.5 % of its vertical velocity's energy "
                  "lies above 20 Hz, the band its soil's mesh resolves there: "
                  "its PPV within the band, 0.002");
  // The fraction kept: A over the two tones' largest sample, 1.588 A (the low-pass leaves 1.5 %
  // of the 50 Hz tone and rings a little: measured 0.64).
  const std::size_t is = r.warnings[0].find(" m/s, is ");
  ASSERT_NE(is, std::string::npos) << r.warnings[0];
  EXPECT_NEAR(std::stod(r.warnings[0].substr(is + 9)), 1.0 / 1.588, 0.015) << r.warnings[0];
  expect_contains(r.warnings[0],
                  "but what it records above 20 Hz (spectrum, band levels, "
                  "scalogram) is the mesh's. Refine the mesh along the path");
  EXPECT_EQ(r.warnings[0].find("mostly"), std::string::npos) << r.warnings[0];
  expect_contains(r.warnings[1],
                  "lies above 2 Hz, the band its soil's mesh resolves there: its "
                  "raw PPV (0.002 m/s) is mostly the mesh's; within the band ");
}

// The older surface receivers: one vertical column "d=<distance> m [m/s]" each, no summary.json
// needed (the distance is in the name); PPV_3c is not available (nan, null in post.json).
TEST(PostRun, DistanceColumnsGiveVerticalOnlyResults) {
  const fs::path dir = fresh_dir();
  write_csv(dir / "receivers.csv", {"d=2.500000 m [m/s]", "d=7.500000 m [m/s]"},
            {sine_at_fs(kA, 25.0), sine_at_fs(kA / 3, 20.0)});
  PostOptions options;
  options.velocity_reference = kVelocityRefVdb;
  const PostResult r = post_process(dir, options);
  const auto ppv = read_rows(dir / "post" / "ppv.csv");
  ASSERT_EQ(ppv.size(), 2u);
  EXPECT_EQ(ppv[0].at("receiver"), "d=2.5 m");
  EXPECT_EQ(ppv[1].at("receiver"), "d=7.5 m");
  EXPECT_NEAR(number(ppv[0], "PPV_z [m/s]"), kA, 1e-8 * kA);
  EXPECT_TRUE(std::isnan(number(ppv[0], "PPV_3c [m/s]")));
  EXPECT_NEAR(number(ppv[1], "distance [m]"), 7.5, 1e-12);
  // CWT at the receivers nearest 2.5 m and 5 m: both of them.
  EXPECT_TRUE(fs::exists(dir / "post" / "cwt_d=2.5_m.csv"));
  EXPECT_TRUE(fs::exists(dir / "post" / "cwt_d=7.5_m.csv"));
  const json report = json::parse(std::ifstream(dir / "post" / "post.json"));
  EXPECT_EQ(report["source"]["form"], "distances");
  EXPECT_TRUE(report["receivers"][0]["ppv_3c_m_s"].is_null());
  // Band levels in VdB: the 25 Hz band of d=2.5 m.
  const auto bands = read_rows(dir / "post" / "third_octave.csv");
  for (const auto& b : bands) {
    if (b.at("band [Hz]") != "25") continue;
    EXPECT_NEAR(number(b, "d=2.5 m vz L_v [dB re 2.54e-08 m/s]"),
                20.0 * std::log10(kA / std::sqrt(2.0) / 2.54e-8), 1e-6);
  }
  EXPECT_EQ(r.files.size(), 6u);  // ppv, spectra, third_octave, two CWTs, post.json
}

// A run that diverged: the rows from the first non-finite value on are left out, with a warning.
TEST(PostRun, DivergedRecordIsCutWithAWarning) {
  const fs::path dir = fresh_dir();
  std::vector<double> v = sine_at_fs(kA, 25.0);
  for (std::size_t k = 1500; k < kN; ++k) v[k] = k == 1500 ? 1e30 * 1e300 : std::nan("");
  write_csv(dir / "receivers.csv", {"d=2.500000 m [m/s]"}, {v});
  const PostResult r = post_process(dir);
  ASSERT_FALSE(r.warnings.empty());
  expect_contains(r.warnings.front(), "not finite from t = 1.5 s (the run diverged)");
  EXPECT_EQ(r.report["sampling"]["samples"], 1500u);
  EXPECT_NEAR(r.report["receivers"][0]["ppv_z_m_s"].get<double>(), kA, 1e-8 * kA);
}

// The same record beside a summary.json of a run that completed: the file is blamed, not the run
// (issue #30 item 5: a message blames the right thing).
TEST(PostRun, ANonFiniteRecordOfACompletedRunBlamesTheFile) {
  const fs::path dir = fresh_dir();
  std::vector<double> v = sine_at_fs(kA, 25.0);
  v[1500] = std::nan("");
  write_csv(dir / "receivers.csv", {"d=2.500000 m [m/s]"}, {v});
  std::ofstream(dir / "summary.json") << R"({"status": "completed"})";
  EXPECT_EQ(message_of([&] { post_process(dir); }),
            "receivers.csv in '" + dir.string() +
                "': column 'd=2.500000 m [m/s]' is not finite at t = 1.5 s (data row 1501), but "
                "summary.json says the run completed, which writes finite numbers only: the file "
                "was damaged or edited after the run. Rerun the scenario");
  std::ofstream(dir / "summary.json") << R"({"status": "failed"})";
  EXPECT_NO_THROW(post_process(dir));  // cut with a warning, as without a summary
}

// A column "d=<distance> m [m/s]" whose distance is not finite is no receiver: "d=-inf m" was one,
// at -inf in ppv.csv (found by the post fuzz target: tests/fuzz/regressions/post/).
TEST(PostRun, ADistanceColumnThatIsNotFiniteIsNoReceiver) {
  const fs::path dir = fresh_dir();
  write_csv(dir / "receivers.csv", {"d=-inf m [m/s]", "d=nan m [m/s]"},
            {sine_at_fs(kA, 25.0), sine_at_fs(kA, 25.0)});
  EXPECT_EQ(message_of([&] { post_process(dir); }),
            "receivers.csv in '" + dir.string() +
                "' has no receiver velocity column: expected '<name> vz [m/s]' or "
                "'d=<distance> m [m/s]', found 'd=-inf m [m/s]', 'd=nan m [m/s]'. Rerun with "
                "receivers in the scenario (outputs.receivers)");
}

// The CWT's zero padding for f_min is 6 wavelet scales, 5.8 s at 1 Hz at any step: at a step of
// 1e-300 s that was 1e300 samples, converted to a size (undefined; found by the post fuzz
// target). A record of a step so short that the padding passes 64 records (and 65536 samples)
// has its f_min raised to what fits, and is transformed from there.
TEST(PostRun, ARecordOfATinyStepHasItsCwtFromAHigherFrequency) {
  const fs::path dir = fresh_dir();
  const double dt = std::ldexp(1.0, -20);  // s, exact in binary: the grid's step is exactly it
  std::ofstream out(dir / "receivers.csv");
  out << "t [s],d=2.5 m [m/s]\n";
  for (int k = 0; k < 200; ++k) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g,%.9g\n", k * dt, kA * std::sin(0.1 * k));
    out << buf;
  }
  out.close();
  const PostResult r = post_process(dir);
  EXPECT_THAT(r.warnings,
              ::testing::Contains("CWT: f_min raised from 1 Hz to 92.9292908 Hz: at the record's "
                                  "step of 9.53674316e-07 s its wavelet needs 6090214 samples of "
                                  "zero padding, more than 65536 (64 times the record's samples, "
                                  "at least 65536)"));
  EXPECT_DOUBLE_EQ(r.report["options"]["cwt_f_min_hz"].get<double>(), 6090214.0 / 65536.0);
  ASSERT_EQ(r.report["cwt"].size(), 1u);  // transformed from there
  // At a step of 1e-300 s nothing is left below f_max: the CWT is skipped, and said so.
  std::ofstream tiny(dir / "receivers.csv");
  tiny << "t [s],d=2.5 m [m/s]\n";
  for (int k = 0; k < 50; ++k) tiny << k << "e-300," << kA * std::sin(0.1 * k) << "\n";
  tiny.close();
  fs::remove_all(dir / "post");
  const PostResult none = post_process(dir);
  EXPECT_TRUE(none.report["cwt"].empty());
  EXPECT_THAT(none.warnings, ::testing::Contains(::testing::HasSubstr("CWT skipped: f_min = ")));
}

// The peak's quarter period over a record of 1e308 s is 4e308 s, infinite: its frequency was 0 Hz
// and the DIN 4150-3 guide values refused it, an exception out of post_process instead of the
// indicators (found by the post fuzz target: tests/fuzz/regressions/post/). The spectrum's
// dominant frequency stands in, and with none there are no guide values, as for any record.
TEST(PostRun, AHalfCycleOfNoFrequencyGivesNoGuideValues) {
  const fs::path dir = fresh_dir();
  std::ofstream(dir / "receivers.csv") << "t [s],d=2.5 m [m/s]\n0,0\n1e+308,0.0314\n";
  const PostResult r = post_process(dir);
  EXPECT_THAT(r.warnings, ::testing::Contains("receiver 'd=2.5 m': no spectral content above 1 "
                                              "Hz, so no dominant frequency and no guide values"));
  EXPECT_TRUE(r.report["receivers"][0]["dominant_frequency_hz"].is_null());
  EXPECT_TRUE(r.report["receivers"][0]["din4150_3"][0]["guide_m_s"].is_null());
}

TEST(PostRun, MissingFileOrColumnSaysWhatWhereAndTheFix) {
  const fs::path dir = fresh_dir();
  std::string m = message_of([&] { post_process(dir); });
  expect_contains(m, "no receivers.csv in '" + dir.string() + "'");
  expect_contains(m, "outputs.receivers");

  m = message_of([&] { post_process(dir / "nowhere"); });
  expect_contains(m, "does not exist");

  // A probe receiver without its vy column.
  write_csv(dir / "receivers.csv", {"x vx [m/s]", "x vz [m/s]"},
            {sine_at_fs(kA, 25.0), sine_at_fs(kA, 25.0)});
  m = message_of([&] { post_process(dir); });
  expect_contains(m, "receivers.csv in '" + dir.string() + "' has no column 'x vy [m/s]'");
  expect_contains(m, "Rerun the scenario");

  // Columns that are no receivers at all.
  write_csv(dir / "receivers.csv", {"something [N]"}, {sine_at_fs(kA, 25.0)});
  m = message_of([&] { post_process(dir); });
  expect_contains(m, "has no receiver velocity column");
  expect_contains(m, "'something [N]'");

  // A named probe whose distance nothing gives (no summary.json).
  write_csv(dir / "receivers.csv", {"x vx [m/s]", "x vy [m/s]", "x vz [m/s]"},
            {sine_at_fs(kA, 25.0), sine_at_fs(kA, 25.0), sine_at_fs(kA, 25.0)});
  m = message_of([&] { post_process(dir); });
  expect_contains(m, "summary.json is missing in '" + dir.string() + "'");
  expect_contains(m, "distance of receiver 'x'");

  // An unknown CWT receiver.
  write_csv(dir / "receivers.csv", {"d=2.500000 m [m/s]"}, {sine_at_fs(kA, 25.0)});
  PostOptions options;
  options.cwt_receivers = {"d=3 m"};
  m = message_of([&] { post_process(dir, options); });
  expect_contains(m, "CWT receiver 'd=3 m' is not in receivers.csv");
  expect_contains(m, "'d=2.5 m'");
}

}  // namespace
}  // namespace rumble::post
