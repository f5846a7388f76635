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

}  // namespace
