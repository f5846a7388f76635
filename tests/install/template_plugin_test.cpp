// The template plugin, built out of tree against the installed SDK (build_template.cmake), loads
// through the engine's PluginRegistry and works through its C table: create, accept a layout,
// initialize, advance one step, read the motion, compared with an independent solution.
#include <gtest/gtest.h>
#include <rumble/abi.h>

#include <cmath>
#include <complex>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "elf_symbols.hpp"
#include "plugin/registry.hpp"

namespace {

constexpr double kStiffness = 2.0e6;  // N/m
constexpr double kDamping = 1.0e5;    // N s/m, time constant c/k = 0.05 s

class TemplatePlugin : public testing::Test {
 protected:
  void SetUp() override {
    registry_.load_library(TEMPLATE_PLUGIN);
    const rumble::ComponentType* type = registry_.find(RUMBLE_KIND_SOIL, "template_soil");
    ASSERT_NE(type, nullptr) << "template_soil.so provides no soil type 'template_soil'";
    api_ = static_cast<const rumble_soil_api*>(type->factory().api);
    host_.struct_size = sizeof(rumble_host);
    host_.abi_minor = RUMBLE_ABI_MINOR;
    host_.scenario_dir = ".";
    const std::string params = "{\"stiffness\": " + std::to_string(kStiffness) +
                               ", \"damping\": " + std::to_string(kDamping) + "}";
    const char* error = nullptr;
    ASSERT_EQ(type->factory().create(params.c_str(), &host_, &instance_, &error), RUMBLE_OK)
        << (error != nullptr ? error : "");
    const std::vector<rumble_footprint> fp{{0.0, 0.0, 2.6, 0.25}, {0.6, 0.0, 2.6, 0.25}};
    ASSERT_EQ(api_->accept_layout(instance_, fp.data(), fp.size()), RUMBLE_OK);
  }
  void TearDown() override {
    if (instance_ != nullptr) api_->common.destroy(instance_);
  }
  std::string last_message() const { return api_->common.last_message(instance_); }

  rumble::PluginRegistry registry_;
  const rumble_soil_api* api_ = nullptr;
  rumble_host host_{};
  rumble_instance* instance_ = nullptr;
};

/// c u' + k u = F(s), F(s) = a0 + a1 (s/H) + a2 (s/H)^2, by RK4 with many steps: an answer
/// independent of the plugin's closed form. Returns u(H) and v(H).
std::pair<double, double> reference(double u0, double H, double a0, double a1, double a2) {
  const auto force = [&](double s) { return a0 + a1 * (s / H) + a2 * (s / H) * (s / H); };
  const auto rate = [&](double s, double u) { return (force(s) - kStiffness * u) / kDamping; };
  const int steps = 4000;
  const double h = H / steps;
  double u = u0;
  for (int j = 0; j < steps; ++j) {
    const double s = j * h;
    const double r1 = rate(s, u), r2 = rate(s + h / 2, u + h / 2 * r1);
    const double r3 = rate(s + h / 2, u + h / 2 * r2), r4 = rate(s + h, u + h * r3);
    u += h / 6 * (r1 + 2 * r2 + 2 * r3 + r4);
  }
  return {u, rate(H, u)};
}

TEST_F(TemplatePlugin, InitializesAtStaticEquilibrium) {
  const std::vector<double> f{8.0e4, 6.0e4};  // N, compressive
  std::vector<double> u(2);
  ASSERT_EQ(api_->initialize(instance_, 0.0, f.data(), u.data(), 2), RUMBLE_OK);
  EXPECT_DOUBLE_EQ(u[0], 8.0e4 / kStiffness);
  EXPECT_DOUBLE_EQ(u[1], 6.0e4 / kStiffness);
}

// One macro step with a quadratic force waveform, from short (x = kH/c << 1, the series branch)
// to long (x >> 1) steps.
TEST_F(TemplatePlugin, AdvancesOneStepExactly) {
  for (const double H : {1.0e-4, 5.0e-3, 2.5e-2, 0.2, 1.0}) {
    SCOPED_TRACE("H = " + std::to_string(H));
    const std::vector<double> f_static{8.0e4, 6.0e4};
    std::vector<double> u(2), v(2);
    ASSERT_EQ(api_->initialize(instance_, 0.0, f_static.data(), u.data(), 2), RUMBLE_OK);
    // Channel i: a0 + a1 tau + a2 tau^2; coefficients laid out coeff[k n + i].
    const std::vector<double> coeff{9.0e4, 6.0e4, -2.0e4, 1.0e4, 5.0e3, -8.0e3};
    const rumble_waveform force{2, 2, coeff.data()};
    ASSERT_EQ(api_->advance(instance_, 0.0, H, &force), RUMBLE_OK) << last_message();
    ASSERT_EQ(api_->motion(instance_, u.data(), v.data(), 2), RUMBLE_OK);
    for (std::size_t i = 0; i < 2; ++i) {
      const auto [u_ref, v_ref] =
          reference(f_static[i] / kStiffness, H, coeff[i], coeff[2 + i], coeff[4 + i]);
      EXPECT_NEAR(u[i], u_ref, 1e-9 * std::abs(u_ref));
      EXPECT_NEAR(v[i], v_ref, 1e-7 * 1.0e5 / kDamping);  // scale: |F| / c
    }
  }
}

TEST_F(TemplatePlugin, SaveRestoreRepeatsAStep) {
  const std::vector<double> f{5.0e4, 5.0e4};
  std::vector<double> u(2), v(2), u_first(2), v_first(2);
  ASSERT_EQ(api_->initialize(instance_, 0.0, f.data(), u.data(), 2), RUMBLE_OK);
  std::uint64_t n = 0;
  ASSERT_EQ(api_->common.state_size(instance_, &n), RUMBLE_OK);
  ASSERT_EQ(n, 4u);
  std::vector<double> state(n);
  ASSERT_EQ(api_->common.save_state(instance_, state.data(), n), RUMBLE_OK);
  const std::vector<double> coeff{7.0e4, 3.0e4};
  const rumble_waveform force{0, 2, coeff.data()};
  ASSERT_EQ(api_->advance(instance_, 0.0, 0.01, &force), RUMBLE_OK);
  ASSERT_EQ(api_->motion(instance_, u_first.data(), v_first.data(), 2), RUMBLE_OK);
  ASSERT_EQ(api_->common.restore_state(instance_, state.data(), n), RUMBLE_OK);
  ASSERT_EQ(api_->advance(instance_, 0.0, 0.01, &force), RUMBLE_OK);
  ASSERT_EQ(api_->motion(instance_, u.data(), v.data(), 2), RUMBLE_OK);
  EXPECT_EQ(u, u_first);
  EXPECT_EQ(v, v_first);
}

TEST_F(TemplatePlugin, ReceptanceIsDiagonalSpringDashpot) {
  const double f_hz = 12.5;
  std::vector<double> re(4), im(4);
  ASSERT_EQ(api_->frequency_response(instance_, f_hz, re.data(), im.data(), 2), RUMBLE_OK);
  const std::complex<double> h =
      1.0 / std::complex<double>(kStiffness, 2.0 * 3.14159265358979323846 * f_hz * kDamping);
  for (std::size_t k : {0u, 3u}) {
    EXPECT_NEAR(re[k], h.real(), 1e-15);
    EXPECT_NEAR(im[k], h.imag(), 1e-15);
  }
  EXPECT_EQ(re[1], 0.0);
  EXPECT_EQ(im[2], 0.0);
}

TEST_F(TemplatePlugin, WrongChannelCountIsAnErrorWithReason) {
  const std::vector<double> coeff{1.0, 2.0, 3.0};
  const rumble_waveform force{0, 3, coeff.data()};
  EXPECT_EQ(api_->advance(instance_, 0.0, 0.01, &force), RUMBLE_ERROR);
  EXPECT_EQ(last_message(), "advance: force waveform has 3 entries, expected 2");
}

// rumble_add_plugin() from the installed package hides everything but the entry point.
TEST(TemplatePluginLibrary, ExportsOnlyTheEntryPoint) {
  const auto symbols = rumble::test::defined_dynamic_symbols(READELF, TEMPLATE_PLUGIN);
  ASSERT_EQ(symbols.size(), 1u) << rumble::test::describe(symbols);
  EXPECT_EQ(symbols[0].name, "rumble_plugin_entry");
}

}  // namespace
