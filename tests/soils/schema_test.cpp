// The params schemas users read with `rumble schema winkler|clm`: JSON Schema draft 7, closed,
// every number with its unit and physical range (both bounds: docs/scenario.md, "Limits"), the two
// ways of giving the parameters as alternatives, and the formulas named with their sources.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <regex>
#include <string>

#include "soil_harness.hpp"

namespace rumble::test {
namespace {

using nlohmann::json;

json schema_of(const std::string& type) {
  return json::parse(soil_factory(type).params_schema);
}

/// Every number property (nested too) states a unit in brackets and a lower and an upper bound.
void expect_numbers_have_units_and_ranges(const json& object, const std::string& where) {
  EXPECT_EQ(object.at("additionalProperties"), false) << where;
  for (const auto& [name, p] : object.at("properties").items()) {
    const std::string at = where + "/" + name;
    ASSERT_TRUE(p.contains("description")) << at;
    if (p.at("type") == "number") {
      EXPECT_TRUE(
          std::regex_search(p.at("description").get<std::string>(), std::regex(R"(\[[^\]]+\])")))
          << at << ": no [unit]";
      EXPECT_TRUE(p.contains("minimum") || p.contains("exclusiveMinimum")) << at;
      EXPECT_TRUE(p.contains("maximum") || p.contains("exclusiveMaximum")) << at;
    }
    if (p.at("type") == "array") expect_numbers_have_units_and_ranges(p.at("items"), at + "/items");
  }
}

// [0, 0.495]: nearer 0.5 the soil is incompressible and c_p grows without bound.
void expect_poisson_range(const json& nu) {
  EXPECT_EQ(nu.at("minimum"), 0);
  EXPECT_EQ(nu.at("maximum"), 0.495);
}

void expect_range(const json& p, double lo, double hi, const std::string& key) {
  EXPECT_EQ(p.at("minimum"), lo) << key;
  EXPECT_EQ(p.at("maximum"), hi) << key;
}

TEST(SoilSchema, WinklerAndClmSchemasAreClosedDraft7WithUnits) {
  for (const char* type : {"winkler", "clm"}) {
    SCOPED_TRACE(type);
    const json s = schema_of(type);
    EXPECT_EQ(s.at("$schema"), "http://json-schema.org/draft-07/schema#");
    EXPECT_EQ(s.at("type"), "object");
    expect_numbers_have_units_and_ranges(s, "");
    expect_poisson_range(s.at("properties").at("nu"));
    expect_poisson_range(s.at("properties").at("layers").at("items").at("properties").at("nu"));
    expect_range(s.at("properties").at("E"), 1e5, 1e12, "E");  // peat to hard rock [Pa]
    expect_range(s.at("properties").at("rho"), 500, 5000, "rho");
    expect_range(s.at("properties").at("max_step"), 1e-7, 1, "max_step");
    // Direct or from soil: exactly one of two required sets.
    ASSERT_EQ(s.at("oneOf").size(), 2u);
    EXPECT_EQ(s.at("oneOf")[1].at("required"), json({"E", "nu", "rho"}));
  }
}

TEST(SoilSchema, DirectParametersAndTheirFormulas) {
  const json w = schema_of("winkler");
  EXPECT_EQ(w.at("oneOf")[0].at("required"), json({"k", "c"}));
  expect_range(w.at("properties").at("k"), 1e4, 1e13, "k");
  expect_range(w.at("properties").at("c"), 0, 1e10, "c");
  const json c = schema_of("clm");
  EXPECT_EQ(c.at("oneOf")[0].at("required"), json({"m_f", "k_f", "c_f", "k_c", "c_c"}));
  expect_range(c.at("properties").at("k_f"), 1e4, 1e13, "k_f");
  expect_range(c.at("properties").at("m_f"), 0, 1e6, "m_f");
  expect_range(c.at("properties").at("k_c"), 0, 1e13, "k_c");
  for (const char* key : {"c_f", "c_c"}) expect_range(c.at("properties").at(key), 0, 1e10, key);
  // The sources are named where users read them.
  const auto text = [](const json& s, const char* key) {
    return s.at("properties").at(key).at("description").get<std::string>();
  };
  EXPECT_NE(text(w, "k").find("Gazetas (1991)"), std::string::npos);
  EXPECT_NE(text(w, "c").find("Lysmer"), std::string::npos);
  EXPECT_NE(text(w, "m").find("Wolf"), std::string::npos);
  EXPECT_NE(text(c, "k_f").find("(1 - r) / (1 + r)"), std::string::npos);
  EXPECT_NE(text(c, "k_c").find("r / (1 - r^2)"), std::string::npos);
  EXPECT_NE(text(c, "layers").find("Boussinesq"), std::string::npos);
}

}  // namespace
}  // namespace rumble::test
