// rumble::Params reads a component's params with the schema as the one declaration of each
// parameter's default (docs/plugin-guide.md, "Each parameter is declared once").
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <rumble/params.hpp>
#include <stdexcept>
#include <string>

namespace {

using ::testing::HasSubstr;

constexpr const char* kSchema = R"({
  "type": "object",
  "definitions": {
    "spring": {"type": "object", "default": {},
               "properties": {"k": {"type": "number", "default": 2.5e7}}}
  },
  "properties": {
    "mass": {"type": "number", "default": 1000},
    "name": {"type": "string"},
    "mesh": {"type": "object", "default": {},
             "properties": {"f_max": {"type": "number", "default": 80},
                            "shape": {"enum": ["box", "hemisphere"], "default": "hemisphere"}}},
    "primary": {"$ref": "#/definitions/spring"}
  },
  "allOf": [{"properties": {"gravity": {"type": "number", "default": 9.81}}}]
})";

TEST(Params, AGivenValueWinsOverTheDefault) {
  const rumble::Params p(R"({"mass": 500})", kSchema);
  EXPECT_EQ(p.get<double>("mass"), 500.0);
  EXPECT_TRUE(p.has("mass"));
}

TEST(Params, AnAbsentKeyReadsTheSchemasDefault) {
  const rumble::Params p("{}", kSchema);
  EXPECT_EQ(p.get<double>("mass"), 1000.0);
  EXPECT_FALSE(p.has("mass")) << "has() tells what the user set, not what defaults fill";
  EXPECT_EQ(p.get<double>("gravity"), 9.81) << "a property declared in allOf";
}

TEST(Params, NestedObjectsReadTheirOwnDefaults) {
  const rumble::Params p(R"({"mesh": {"shape": "box"}})", kSchema);
  const rumble::Params mesh = p.object("mesh");
  EXPECT_EQ(mesh.get<std::string>("shape"), "box");
  EXPECT_EQ(mesh.get<double>("f_max"), 80.0);
  EXPECT_EQ(p.object("primary").get<double>("k"), 2.5e7) << "through a local $ref";
  EXPECT_EQ(rumble::Params("{}", kSchema).object("mesh").get<double>("f_max"), 80.0)
      << "an absent object is its default, read against its schema";
}

TEST(Params, AKeyWithNeitherValueNorDefaultIsAPluginBugWithItsPointer) {
  const rumble::Params p(R"({"mesh": {}})", kSchema);
  try {
    (void)p.get<std::string>("name");
    FAIL() << "read a value that does not exist";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "params/name: missing, and the schema gives no default");
  }
  try {
    (void)p.object("mesh").get<double>("radius");
    FAIL() << "read a value that does not exist";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("params/mesh/radius: missing"));
  }
}

TEST(Params, AValueOfTheWrongTypeNamesItsPointer) {
  const rumble::Params p(R"({"mesh": {"f_max": "high"}})", kSchema);
  try {
    (void)p.object("mesh").get<double>("f_max");
    FAIL() << "read a string as a number";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("params/mesh/f_max: "));
  }
}

TEST(Params, WithoutASchemaOnlyGivenValuesExist) {
  const rumble::Params p(R"({"mass": 2})");
  EXPECT_EQ(p.get<double>("mass"), 2.0);
  EXPECT_EQ(p.get_or<double>("stiffness", 3.0), 3.0) << "a derived default, stated by the caller";
  EXPECT_THROW((void)p.get<double>("stiffness"), std::invalid_argument);
}

constexpr const char* kChoiceSchema = R"({
  "type": "object",
  "properties": {
    "type": {"enum": ["spring", "pml"], "default": "spring"},
    "pml": {"type": "object", "properties": {"elements": {"type": "number", "default": 8}}},
    "alpha": {"type": "number"},
    "step": {"type": "number"}
  },
  "allOf": [
    {"if": {"required": ["type"], "properties": {"type": {"const": "pml"}}},
     "then": {"properties": {"pml": {"default": {}}, "alpha": {"default": 1.5}}}}
  ]
})";

TEST(Params, ADefaultOnlyOneChoiceHasFollowsTheChoice) {
  const rumble::Params pml(R"({"type": "pml"})", kChoiceSchema);
  EXPECT_EQ(pml.get<double>("alpha"), 1.5) << "the then-branch's default";
  EXPECT_EQ(pml.object("pml").get<double>("elements"), 8.0);
  const rumble::Params spring("{}", kChoiceSchema);
  EXPECT_FALSE(spring.optional<double>("alpha").has_value())
      << "the if requires type, absent here: the choice is not pml";
  EXPECT_THROW((void)spring.get<double>("alpha"), std::invalid_argument);
}

TEST(Params, OptionalGivesTheValueTheDefaultOrNothing) {
  const rumble::Params p(R"({"step": 0.5})", kChoiceSchema);
  EXPECT_EQ(p.optional<double>("step"), 0.5);
  EXPECT_EQ(rumble::Params("{}", kSchema).optional<double>("mass"), 1000.0);
  EXPECT_FALSE(rumble::Params("{}", kChoiceSchema).optional<double>("step").has_value());
}

TEST(Params, TheComponentsNamePrefixesEveryMessage) {
  const rumble::Params p(R"({"mesh": {"f_max": "high"}})", kSchema, "acme_soil");
  EXPECT_EQ(p.object("mesh").pointer("f_max"), "acme_soil: params/mesh/f_max: ");
  try {
    (void)p.get<std::string>("name");
    FAIL() << "read a value that does not exist";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "acme_soil: params/name: missing, and the schema gives no default");
  }
}

}  // namespace
