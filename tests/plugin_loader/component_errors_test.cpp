// A component's failures reach the host in the plugin's own words: exceptions in create and in
// calls become statuses at the C table (plugin.hpp's wrappers: rumble::Discard -> DISCARD, any
// other exception -> ERROR, warn_caller -> WARNING, text in last_message), and the engine's
// Instance turns them into errors that name the component and keep that text.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "fixture_paths.hpp"
#include "plugin/instance.hpp"
#include "plugin/registry.hpp"
#include "soil_fixture.hpp"

namespace {

namespace fs = std::filesystem;
using testing::HasSubstr;

class FaultySoil : public testing::Test {
 protected:
  void SetUp() override {
    registry_.load_library(fixture::faulty);
    type_ = registry_.find(RUMBLE_KIND_SOIL, "loader_test_faulty");
    ASSERT_NE(type_, nullptr);
    api_ = static_cast<const rumble_soil_api*>(type_->factory().api);
  }
  void TearDown() override {
    if (instance_ != nullptr) api_->common.destroy(instance_);
  }

  /// create() with params; returns its status, the error text in error_.
  rumble_status create(const char* params) {
    const char* error = nullptr;
    const rumble_status s = type_->factory().create(params, &host_.host, &instance_, &error);
    error_ = error != nullptr ? error : "";
    return s;
  }
  /// A created instance with n footprints, initialized at rest.
  void create_ready(std::size_t n) {
    ASSERT_EQ(create("{}"), RUMBLE_OK) << error_;
    const auto fp = rumble::test::footprints(n);
    ASSERT_EQ(api_->accept_layout(instance_, fp.data(), n), RUMBLE_OK);
    std::vector<double> f(n, 0.0), u(n, 0.0);
    ASSERT_EQ(api_->initialize(instance_, 0.0, f.data(), u.data(), n), RUMBLE_OK);
  }
  rumble_status advance(double H, std::vector<double> force) {
    const rumble::test::ConstantForce f(std::move(force));
    return api_->advance(instance_, 0.0, H, &f.waveform);
  }
  double u0() {
    std::vector<double> u(2), v(2);
    EXPECT_EQ(api_->motion(instance_, u.data(), v.data(), 2), RUMBLE_OK);
    return u[0];
  }
  std::string last_message() const { return api_->common.last_message(instance_); }

  rumble::PluginRegistry registry_;
  const rumble::ComponentType* type_ = nullptr;
  const rumble_soil_api* api_ = nullptr;
  rumble::test::RecordingHost host_;
  rumble_instance* instance_ = nullptr;
  std::string error_;
};

TEST_F(FaultySoil, CreateThrowingStdExceptionIsErrorWithItsText) {
  EXPECT_EQ(create(R"({"create":"throw"})"), RUMBLE_ERROR);
  EXPECT_EQ(instance_, nullptr);
  EXPECT_EQ(error_, "params/create: told to throw; remove the key");
}

TEST_F(FaultySoil, CreateThrowingNonStdExceptionIsErrorToo) {
  EXPECT_EQ(create(R"({"create":"throw_int"})"), RUMBLE_ERROR);
  EXPECT_EQ(instance_, nullptr);
  EXPECT_EQ(error_, "unknown exception (not derived from std::exception)");
}

TEST_F(FaultySoil, HostLogReachesTheHost) {
  ASSERT_EQ(create("{}"), RUMBLE_OK);
  ASSERT_EQ(host_.lines.size(), 1u);
  EXPECT_EQ(host_.lines[0].first, RUMBLE_LOG_INFO);
  EXPECT_EQ(host_.lines[0].second, "loader_test_faulty created");
}

TEST_F(FaultySoil, CallThrowingIsErrorWithLastMessage) {
  create_ready(2);
  EXPECT_EQ(advance(0.1, {-1.0, 0.0}), RUMBLE_ERROR);
  EXPECT_EQ(last_message(), "footprint 0: force -1.000000 N is tensile; the soil cannot pull");
}

TEST_F(FaultySoil, DiscardLeavesStateUnchanged) {
  create_ready(2);
  ASSERT_EQ(advance(0.1, {2.0, 0.0}), RUMBLE_OK);
  EXPECT_DOUBLE_EQ(u0(), 0.2);
  EXPECT_EQ(advance(2.0, {2.0, 0.0}), RUMBLE_DISCARD);
  EXPECT_EQ(last_message(), "step too long; at most 1 s");
  EXPECT_DOUBLE_EQ(u0(), 0.2);
  EXPECT_EQ(advance(0.1, {2.0, 0.0}), RUMBLE_OK) << "a refused step may be retried";
  EXPECT_DOUBLE_EQ(u0(), 0.4);
}

TEST_F(FaultySoil, WarningMeansDoneAndExplained) {
  create_ready(2);
  EXPECT_EQ(advance(0.5, {2.0, 0.0}), RUMBLE_WARNING);
  EXPECT_EQ(last_message(), "a step of exactly 0.5 s is suspicious");
  EXPECT_DOUBLE_EQ(u0(), 1.0);
}

// DISCARD means only "step refused" (ABI 1.1): an optional call that is not offered is not
// declared, the host does not make it, and made anyway it is an error that says so.
TEST_F(FaultySoil, OptionalCallsNotOfferedAreErrorsAndUndeclared) {
  create_ready(2);
  std::vector<double> re(4), im(4);
  EXPECT_EQ(api_->frequency_response(instance_, 10.0, re.data(), im.data(), 2), RUMBLE_ERROR);
  EXPECT_EQ(last_message(), "frequency response not offered");
  const rumble_receiver r{5.0, 2.5};
  EXPECT_EQ(api_->set_receivers(instance_, &r, 1), RUMBLE_ERROR);
  EXPECT_EQ(last_message(), "receivers not offered");
  const rumble::Capabilities& caps = type_->capabilities;
  EXPECT_TRUE(caps.declared);
  EXPECT_FALSE(caps.has(RUMBLE_CAP_FREQUENCY_RESPONSE));
  EXPECT_FALSE(caps.has(RUMBLE_CAP_SURFACE_RECEIVERS));
  EXPECT_FALSE(caps.has(RUMBLE_CAP_RECEIVERS));
  std::uint64_t n = 99;
  EXPECT_EQ(api_->common.state_size(instance_, &n), RUMBLE_OK);
  EXPECT_EQ(n, 0u) << "no save/restore unless the component offers it";
}

// ------------------------------------------------ through the engine's Instance wrapper

TEST_F(FaultySoil, EngineReportsCreateFailureWithPluginText) {
  try {
    rumble::SoilInstance soil(*type_, "/soil", nlohmann::json{{"create", "throw"}}, ".");
    FAIL() << "created";
  } catch (const rumble::ConfigError& e) {
    const std::string what = e.what();
    EXPECT_THAT(what, HasSubstr("/soil"));
    EXPECT_THAT(what, HasSubstr("loader_test_faulty"));
    EXPECT_THAT(what, HasSubstr("params/create: told to throw; remove the key"));
    EXPECT_THAT(what, HasSubstr(fs::canonical(fixture::faulty).string()));
  }
}

TEST_F(FaultySoil, EngineReportsCallErrorWithLastMessage) {
  rumble::SoilInstance soil(*type_, "/soil", nlohmann::json::object(), ".");
  soil.accept_layout(rumble::test::footprints(2));
  std::vector<double> f(2, 0.0), u(2, 0.0);
  soil.initialize(0.0, f, u);
  const rumble::test::ConstantForce tensile({-1.0, 0.0});
  try {
    soil.advance(0.0, 0.1, tensile.waveform);
    FAIL() << "no error";
  } catch (const rumble::RunError& e) {
    const std::string what = e.what();
    EXPECT_THAT(what, HasSubstr("loader_test_faulty"));
    EXPECT_THAT(what, HasSubstr("/soil"));
    EXPECT_THAT(what, HasSubstr("advance"));
    EXPECT_THAT(what, HasSubstr("footprint 0: force -1.000000 N is tensile; the soil cannot pull"));
  }
  const rumble::test::ConstantForce too_long({1.0, 1.0});
  EXPECT_THROW(soil.advance(0.0, 2.0, too_long.waveform), rumble::Discarded);
}

}  // namespace

// ------------------------------------------------ what crosses the C table, checked by the host

namespace {

class RawSoil : public testing::Test {
 protected:
  const rumble::ComponentType& type(const char* library, const char* name) {
    registry_.load_library(library);
    const rumble::ComponentType* t = registry_.find(RUMBLE_KIND_SOIL, name);
    EXPECT_NE(t, nullptr);
    return *t;
  }
  /// The message of what `fn` throws as E; "" when it throws nothing.
  template <class E, class Fn>
  static std::string thrown(Fn&& fn) {
    try {
      fn();
    } catch (const E& e) {
      return e.what();
    }
    return "";
  }
  rumble::PluginRegistry registry_;
};

// A C plugin may return NULL from last_message; std::string(NULL) is undefined behaviour and
// libstdc++ throws "basic_string: construction from null is not valid", which hid the call.
TEST_F(RawSoil, NullLastMessageReadsAsNoMessage) {
  rumble::SoilInstance soil(type(fixture::raw, "loader_test_raw"), "/soil",
                            nlohmann::json{{"mode", "null_message"}}, ".");
  const std::string what =
      thrown<rumble::ConfigError>([&] { soil.accept_layout(rumble::test::footprints(3)); });
  EXPECT_THAT(what, HasSubstr("soil 'loader_test_raw' (/soil): accept_layout failed: no message"));
}

TEST_F(RawSoil, NanStaticDisplacementIsRefusedNamingPluginAndCall) {
  rumble::SoilInstance soil(type(fixture::raw, "loader_test_raw"), "/soil",
                            nlohmann::json{{"mode", "nan_static"}}, ".");
  soil.accept_layout(rumble::test::footprints(3));
  std::vector<double> f(3, 1e4), u;
  const std::string what = thrown<rumble::RunError>([&] { soil.initialize(0.0, f, u); });
  EXPECT_THAT(what, HasSubstr("soil 'loader_test_raw' (/soil): initialize returned a static "
                              "displacement that is not finite (nan at 1) from finite inputs"));
  EXPECT_THAT(what, HasSubstr(fs::canonical(fixture::raw).string()));
}

TEST_F(RawSoil, InfiniteVelocityIsRefusedNamingPluginAndCall) {
  rumble::SoilInstance soil(type(fixture::raw, "loader_test_raw"), "/soil",
                            nlohmann::json{{"mode", "inf_velocity"}}, ".");
  soil.accept_layout(rumble::test::footprints(3));
  std::vector<double> u(3), v(3);
  const std::string what = thrown<rumble::RunError>([&] { soil.motion(u.data(), v.data(), 3); });
  EXPECT_THAT(what, HasSubstr("soil 'loader_test_raw' (/soil): motion returned a velocity that "
                              "is not finite (inf at 1) from finite inputs"));
}

TEST_F(RawSoil, ForceThatIsNotFiniteIsADivergenceNotTheSoils) {
  rumble::SoilInstance soil(type(fixture::raw, "loader_test_raw"), "/soil",
                            nlohmann::json::object(), ".");
  soil.accept_layout(rumble::test::footprints(3));
  const rumble::test::ConstantForce force({0.0, std::nan(""), 0.0});
  const std::string what =
      thrown<rumble::RunError>([&] { soil.advance(0.25, 1e-3, force.waveform); });
  EXPECT_THAT(what, HasSubstr("simulation diverged at t = 0.25 s: the footprint force given "
                              "to soil 'loader_test_raw' (/soil) is not finite (footprint 1)"));
}

TEST_F(RawSoil, ExceptionEscapingCreateNamesPluginAndCall) {
  const rumble::ComponentType& t = type(fixture::raw_throw, "loader_test_raw_throw");
  const std::string what = thrown<rumble::RunError>([&] {
    rumble::SoilInstance(t, "/soil", nlohmann::json{{"x", "throw_create"}}, ".");
  });
  EXPECT_THAT(what, HasSubstr("soil 'loader_test_raw_throw' (/soil): create let an exception "
                              "escape through the C interface: raw_throw: create threw"));
}

TEST_F(RawSoil, ExceptionEscapingACallNamesPluginAndCall) {
  rumble::SoilInstance soil(type(fixture::raw_throw, "loader_test_raw_throw"), "/soil",
                            nlohmann::json::object(), ".");
  const std::string what =
      thrown<rumble::ConfigError>([&] { soil.accept_layout(rumble::test::footprints(3)); });
  EXPECT_THAT(what, HasSubstr("soil 'loader_test_raw_throw' (/soil): accept_layout let an "
                              "exception escape through the C interface: raw_throw: "
                              "accept_layout threw"));
}

}  // namespace
