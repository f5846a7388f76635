#include "scenario/schema_print.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>

#include "plugin/registry.hpp"
#include "test_support.hpp"

namespace rumble::scenario {
namespace {

ComponentType component(const std::string& schema) {
  ComponentType t;
  t.kind = RUMBLE_KIND_SOIL;
  t.type_name = "example";
  t.summary = "an example soil";
  t.params_schema = schema;
  return t;
}

std::string printed(const ComponentType& t, bool raw) {
  std::ostringstream os;
  print_schema(os, t, raw);
  return os.str();
}

TEST(ScenarioSchemaPrint, OneRowPerParamInDeclarationOrderWithNestedObjectsDotted) {
  const auto t = component(R"({
    "type": "object", "required": ["k"],
    "properties": {
      "k": {"type": "number", "exclusiveMinimum": 0, "description": "stiffness [N/m]"},
      "mode": {"enum": ["a", "b"], "default": "a", "description": "how"},
      "layer": {"type": "object", "properties": {
        "depth": {"$ref": "#/definitions/len", "default": 1.5}}},
      "nu": {"type": "number", "minimum": 0, "exclusiveMaximum": 0.5, "default": 0.3}
    },
    "definitions": {"len": {"type": "number", "exclusiveMinimum": 0, "description": "[m]"}}
  })");
  EXPECT_EQ(printed(t, false),
            "example (soil type)\n"
            "an example soil\n"
            "\n"
            "params:\n"
            "  name         type    required  default  range         description\n"
            "  k            number  yes                > 0           stiffness [N/m]\n"
            "  mode         enum    no        \"a\"      one of: a, b  how\n"
            "  layer        object  no\n"
            "  layer.depth  number  no                 > 0           [m]\n"
            "  nu           number  no        0.3      [0, 0.5)\n");
}

// A number inside an array or a variant has no row of its own; its range shows in the row of
// what holds it (every number has a range: docs/scenario.md, "Limits").
TEST(ScenarioSchemaPrint, NumbersInsideArraysAndVariantsShowTheirRange) {
  const auto t = component(R"({
    "type": "object",
    "properties": {
      "point": {"type": "array", "minItems": 2, "maxItems": 2,
                "items": {"$ref": "#/definitions/coordinate"}},
      "inertia": {"oneOf": [{"type": "number", "minimum": 0, "maximum": 1e8},
                            {"type": "array", "items": {"type": "array",
                             "items": {"type": "number", "minimum": -1e8, "maximum": 1e8}}}]}
    },
    "definitions": {"coordinate": {"type": "number", "minimum": -100, "maximum": 100}}
  })");
  const std::string out = printed(t, false);
  EXPECT_NE(out.find(">= 2 items, <= 2 items, each [-100, 100]"), std::string::npos) << out;
  EXPECT_NE(out.find("a number [0, 1e+08] or each [-1e+08, 1e+08]"), std::string::npos) << out;
}

// `rumble schema TYPE --json` is for tools: JSON and nothing else (issue #8).
TEST(ScenarioSchemaPrint, RawSchemaIsJsonOnly) {
  const std::string out = printed(component(R"({"type": "object", "required": ["k"]})"), true);
  EXPECT_EQ(out, "{\n  \"type\": \"object\",\n  \"required\": [\n    \"k\"\n  ]\n}\n");
  EXPECT_THROW(printed(component("{oops"), true), std::runtime_error);
}

TEST(ScenarioSchemaPrint, BrokenSchemaIsSaidNotThrown) {
  const std::string out = printed(component("{oops"), false);
  EXPECT_NE(out.find("params: the plugin's schema is not valid JSON"), std::string::npos) << out;
}

TEST(ScenarioSchemaPrint, InTreeVehicle) {
  const auto* t = test::golden_registry().find(RUMBLE_KIND_VEHICLE, "single_wheel");
  if (t == nullptr) GTEST_SKIP() << "single_wheel not built";
  const std::string out = printed(*t, false);
  EXPECT_NE(out.find("single_wheel (vehicle type, plugin "), std::string::npos) << out;
  EXPECT_NE(out.find("wheel_radius  number  no        0.46"), std::string::npos) << out;
}

}  // namespace
}  // namespace rumble::scenario
