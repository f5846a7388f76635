// A library stays mapped while anything made by it lives: every ComponentType, and through it
// every instance, holds a shared_ptr to its LoadedLibrary. Destroying the registry first must
// leave instances working (docs/toolchain.md §3: an object outliving its library's code segfaults).
#include <gtest/gtest.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "fixture_paths.hpp"
#include "plugin/instance.hpp"
#include "plugin/registry.hpp"
#include "soil_fixture.hpp"

namespace {

using rumble::PluginRegistry;

TEST(PluginLifetime, RawInstanceOutlivesRegistry) {
  auto registry = std::make_unique<PluginRegistry>();
  registry->load_library(fixture::faulty);
  const rumble::ComponentType* type = registry->find(RUMBLE_KIND_SOIL, "loader_test_faulty");
  ASSERT_NE(type, nullptr);
  // What an owner of an instance keeps: the library, and pointers into the library's own data.
  std::shared_ptr<const rumble::LoadedLibrary> library = type->library;
  const rumble_factory* factory = &type->factory();
  const auto* api = static_cast<const rumble_soil_api*>(factory->api);
  rumble::test::RecordingHost host;
  rumble_instance* instance = nullptr;
  const char* error = nullptr;
  ASSERT_EQ(factory->create("{}", &host.host, &instance, &error), RUMBLE_OK);

  registry.reset();
  EXPECT_EQ(library.use_count(), 1) << "the registry let go; only this holder is left";

  const auto fp = rumble::test::footprints(2);
  ASSERT_EQ(api->accept_layout(instance, fp.data(), 2), RUMBLE_OK);
  const rumble::test::ConstantForce force({3.0, 1.0});
  ASSERT_EQ(api->advance(instance, 0.0, 0.75, &force.waveform), RUMBLE_OK);
  std::vector<double> u(2), v(2);
  ASSERT_EQ(api->motion(instance, u.data(), v.data(), 2), RUMBLE_OK);
  EXPECT_DOUBLE_EQ(u[0], 2.25);
  EXPECT_DOUBLE_EQ(u[1], 0.75);
  api->common.destroy(instance);  // code of the library, still mapped
}

TEST(PluginLifetime, EngineInstanceOutlivesRegistry) {
  auto registry = std::make_unique<PluginRegistry>();
  registry->load_library(fixture::faulty);
  auto soil = std::make_unique<rumble::SoilInstance>(
      *registry->find(RUMBLE_KIND_SOIL, "loader_test_faulty"), "/soil", nlohmann::json::object(),
      ".");
  registry.reset();

  soil->accept_layout(rumble::test::footprints(2));
  std::vector<double> f{0.0, 0.0}, u(2);
  soil->initialize(0.0, f, u);
  const rumble::test::ConstantForce force({4.0, 2.0});
  soil->advance(0.0, 0.25, force.waveform);
  std::vector<double> v(2);
  soil->motion(u.data(), v.data(), 2);
  EXPECT_DOUBLE_EQ(u[0], 1.0);
  EXPECT_DOUBLE_EQ(u[1], 0.5);
  soil.reset();  // destroy() runs in the library, which this instance alone kept mapped
}

// An engine instance names its type in every error message: it must own that (a copy of its
// ComponentType), not point into the registry, which may be gone or have reallocated its list
// when another library was loaded. Under the asan preset a dangling pointer fails here.
TEST(PluginLifetime, EngineInstanceStillNamesItsTypeAfterRegistry) {
  auto registry = std::make_unique<PluginRegistry>();
  registry->load_library(fixture::faulty);
  rumble::SoilInstance soil(*registry->find(RUMBLE_KIND_SOIL, "loader_test_faulty"), "/soil",
                            nlohmann::json::object(), ".");
  registry.reset();
  EXPECT_EQ(soil.type_name(), "loader_test_faulty");
  // The error path names the type too.
  soil.accept_layout(rumble::test::footprints(1));
  const rumble::test::ConstantForce tensile({-1.0});
  try {
    soil.advance(0.0, 0.1, tensile.waveform);
    FAIL() << "no error";
  } catch (const rumble::RunError& e) {
    EXPECT_NE(std::string(e.what()).find("soil 'loader_test_faulty' (/soil)"), std::string::npos)
        << e.what();
  }
}

// Loading more libraries after an instance exists grows the registry's type list (which may
// move it); the instance must not care.
TEST(PluginLifetime, EngineInstanceUnaffectedByLaterLoads) {
  PluginRegistry registry;
  registry.load_library(fixture::faulty);
  rumble::SoilInstance soil(*registry.find(RUMBLE_KIND_SOIL, "loader_test_faulty"), "/soil",
                            nlohmann::json::object(), ".");
  for (const char* more : {fixture::forged_ok, fixture::dup_a}) registry.load_library(more);
  EXPECT_EQ(soil.type_name(), "loader_test_faulty");
  EXPECT_EQ(soil.type().library->path, registry.libraries().front()->path);
}

}  // namespace
