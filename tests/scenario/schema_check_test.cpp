#include "scenario/schema_check.hpp"

#include <gtest/gtest.h>

namespace rumble::scenario {
namespace {

using nlohmann::json;

// "pointer: message [got] | hint" per issue, in order.
std::vector<std::string> issues(const std::string& schema, const json& value) {
  const SchemaChecker checker(schema);
  std::vector<std::string> out;
  for (const SchemaIssue& i : checker.check(value)) {
    out.push_back(i.pointer + (i.at_key ? " (key)" : "") + ": " + i.message +
                  (i.show_value ? " [got]" : "") + (i.hint.empty() ? "" : " | " + i.hint));
  }
  return out;
}

using Lines = std::vector<std::string>;

const char* kObject = R"({
  "type": "object",
  "additionalProperties": false,
  "required": ["mass", "mode"],
  "properties": {
    "mass": {"type": "number", "exclusiveMinimum": 0, "description": "wheel mass [kg]"},
    "ratio": {"type": "number", "minimum": 0, "exclusiveMaximum": 0.5},
    "count": {"type": "integer", "minimum": 1, "maximum": 32, "default": 4},
    "mode": {"enum": ["fast", "slow", "exact"]},
    "damping": {"type": "number", "minimum": 0},
    "tags": {"type": "array", "minItems": 1, "items": {"type": "string", "minLength": 1}},
    "inner": {"type": "object", "additionalProperties": false, "default": {},
              "properties": {"x": {"type": "number", "default": 1.5}}}
  }
})";

TEST(ScenarioSchemaCheck, ValidValueHasNoIssues) {
  EXPECT_EQ(issues(kObject, json::parse(R"({"mass": 1, "mode": "fast"})")), Lines{});
}

TEST(ScenarioSchemaCheck, EachRuleIsPhrasedFromTheSchemaKeyword) {
  const json value = json::parse(R"({
    "mass": -2.5e7, "ratio": 0.5, "count": 40, "mode": "fats", "tags": [], "damping": "12"
  })");
  EXPECT_EQ(
      issues(kObject, value),
      (Lines{"/count: must be in [1, 32] [got]",
             "/damping: must be a number [got] | remove the quotes: numbers are written "
             "without quotes",
             // A range's hint is the description, which says why (docs/scenario.md, "Limits").
             "/mass: must be > 0 [got] | wheel mass [kg]",
             "/mode: must be one of: fast, slow, exact [got] | did you mean \"fast\"?",
             "/ratio: must be in [0, 0.5) [got]", "/tags: must have at least 1 item, got 0"}));
}

TEST(ScenarioSchemaCheck, ARemovedEnumValueIsToldWhatReplacesIt) {
  // "x-removed" (docs/plugin-guide.md): the fix, not "did you mean" a value that merely looks
  // alike; other values keep the nearest spelling.
  const char* schema = R"({"enum": ["fast", "exact"],
                          "x-removed": {"slow": "was removed in 2.0: \"exact\" replaces it"}})";
  EXPECT_EQ(issues(schema, json("slow")),
            (Lines{": must be one of: fast, exact [got] | \"slow\" was removed in 2.0: \"exact\" "
                   "replaces it"}));
  EXPECT_EQ(issues(schema, json("fats")),
            (Lines{": must be one of: fast, exact [got] | did you mean \"fast\"?"}));
  EXPECT_EQ(issues(schema, json("exact")), Lines{});
}

TEST(ScenarioSchemaCheck, MissingRequiredKeysNameTheKeyAndItsDescription) {
  EXPECT_EQ(issues(kObject, json::object()),
            (Lines{": required key 'mass' is missing | add \"mass\": wheel mass [kg]",
                   ": required key 'mode' is missing"}));
}

TEST(ScenarioSchemaCheck, EveryUnknownKeyIsReportedAtItsKeyWithASuggestion) {
  // valijson names only the first unknown key of an object; all of them are reported (the
  // inner object's first: valijson checks properties before the object's own extra keys).
  const json value = json::parse(R"({"mass": 1, "mode": "slow", "dampng": 1, "zzz": 2,
                                     "inner": {"y": 1}})");
  EXPECT_EQ(issues(kObject, value),
            (Lines{"/inner/y (key): unknown key 'y' | allowed keys: x",
                   "/dampng (key): unknown key 'dampng' | did you mean \"damping\"? allowed "
                   "keys: count, damping, inner, mass, mode, ratio, tags",
                   "/zzz (key): unknown key 'zzz' | allowed keys: count, damping, inner, mass, "
                   "mode, ratio, tags"}));
}

TEST(ScenarioSchemaCheck, AWrongTypeHidesTheValueRulesOfTheSameValue) {
  EXPECT_EQ(
      issues(kObject, json::parse(R"({"mass": "heavy", "mode": 3})")),
      (Lines{"/mass: must be a number [got]", "/mode: must be one of: fast, slow, exact [got]"}));
  EXPECT_EQ(issues(R"({"type": "integer", "const": 1})", json("1")),
            (Lines{": must be an integer [got] | remove the quotes: numbers are written without "
                   "quotes"}));
  EXPECT_EQ(issues(R"({"type": "integer"})", json(20.0)),
            (Lines{": must be an integer [got] | write it without a decimal point or exponent: "
                   "20"}));
}

const char* kVariants = R"({
  "type": "object",
  "properties": {
    "profile": {
      "oneOf": [
        {"type": "object", "additionalProperties": false, "required": ["type"],
         "properties": {"type": {"const": "none"}}},
        {"type": "object", "additionalProperties": false, "required": ["type", "depth"],
         "properties": {"type": {"const": "dip"}, "depth": {"type": "number", "exclusiveMinimum": 0}}},
        {"type": "object", "additionalProperties": false, "required": ["type", "height"],
         "properties": {"type": {"const": "bump"}, "height": {"type": "number", "exclusiveMinimum": 0}}}
      ]
    },
    "order": {"oneOf": [{"type": "integer", "minimum": 0}, {"enum": ["auto"]}]}
  }
})";

TEST(ScenarioSchemaCheck, AFailedOneOfIsExplainedByTheVariantTheValueMeant) {
  EXPECT_EQ(issues(kVariants, json::parse(R"({"profile": {"type": "dip", "dept": 1}})")),
            (Lines{"/profile/dept (key): unknown key 'dept' | did you mean \"depth\"? allowed "
                   "keys: depth, type",
                   "/profile: required key 'depth' is missing"}));
  EXPECT_EQ(issues(kVariants, json::parse(R"({"profile": {"type": "bump", "height": -1}})")),
            (Lines{"/profile/height: must be > 0 [got]"}));
}

TEST(ScenarioSchemaCheck, AValueOfNoAllowedKindListsTheKinds) {
  EXPECT_EQ(issues(kVariants, json::parse(R"({"order": true})")),
            (Lines{"/order: must be an integer or one of auto [got]"}));
  EXPECT_EQ(issues(kVariants, json::parse(R"({"order": -1})")),
            (Lines{"/order: must be >= 0 [got]"}));
}

// The in-tree soils' form: either of two sets of keys.
const char* kKeySets = R"({
  "type": "object", "additionalProperties": false,
  "description": "give k and c, or E, nu and rho",
  "oneOf": [{"required": ["k", "c"]}, {"required": ["E", "nu", "rho"]}],
  "properties": {"k": {"type": "number", "description": "spring [N/m]"}, "c": {"type": "number"},
                 "E": {"type": "number"}, "nu": {"type": "number"}, "rho": {"type": "number"}}
})";

TEST(ScenarioSchemaCheck, AlternativeKeySetsAreNamedUnlessOneIsStarted) {
  EXPECT_EQ(issues(kKeySets, json::object()),
            (Lines{": needs k and c, or E, nu and rho | give k and c, or E, nu and rho"}));
  EXPECT_EQ(issues(kKeySets, json::parse(R"({"nu": 0.3})")),
            (Lines{": required key 'E' is missing", ": required key 'rho' is missing"}));
  EXPECT_EQ(issues(kKeySets, json::parse(R"({"k": 1, "c": 2, "E": 1, "nu": 0.3, "rho": 1})")),
            (Lines{": fits more than one of the alternatives; exactly one is allowed | give k "
                   "and c, or E, nu and rho"}));
  EXPECT_EQ(issues(kKeySets, json::parse(R"({"k": 1, "c": 2})")), Lines{});
}

TEST(ScenarioSchemaCheck, AValueFittingSeveralAlternativesIsTold) {
  EXPECT_EQ(issues(R"({"oneOf": [{"type": "number"}, {"minimum": 0}]})", json(1)),
            (Lines{": fits more than one of the alternatives; exactly one is allowed"}));
}

TEST(ScenarioSchemaCheck, ConditionalVariantsReportOnlyTheBranchTaken) {
  const char* schema = R"({
    "type": "object", "required": ["type"],
    "properties": {"type": {"enum": ["a", "b"]}},
    "allOf": [
      {"if": {"required": ["type"], "properties": {"type": {"const": "a"}}},
       "then": {"additionalProperties": false, "required": ["x"],
                "properties": {"type": {}, "x": {"type": "number", "maximum": 1}}}},
      {"if": {"required": ["type"], "properties": {"type": {"const": "b"}}},
       "then": {"additionalProperties": false,
                "properties": {"type": {}, "y": {"type": "integer", "default": 7}}}}
    ]
  })";
  EXPECT_EQ(issues(schema, json::parse(R"({"type": "a", "x": 2, "y": 1})")),
            (Lines{"/x: must be <= 1 [got]", "/y (key): unknown key 'y' | allowed keys: type, x"}));
  EXPECT_EQ(issues(schema, json::parse(R"({"type": "c"})")),
            (Lines{"/type: must be one of: a, b [got]"}));

  const SchemaChecker checker(schema);
  json b = json::parse(R"({"type": "b"})");
  checker.fill_defaults(b);
  EXPECT_EQ(b, json::parse(R"({"type": "b", "y": 7})"));
  json a = json::parse(R"({"type": "a", "x": 0})");
  checker.fill_defaults(a);
  EXPECT_EQ(a, json::parse(R"({"type": "a", "x": 0})"));
}

TEST(ScenarioSchemaCheck, RefsAreFollowedForRulesDescriptionsAndDefaults) {
  const char* schema = R"({
    "type": "object",
    "properties": {"a": {"$ref": "#/definitions/pos"}, "b": {"$ref": "#/definitions/pos"}},
    "required": ["b"],
    "definitions": {"pos": {"type": "number", "exclusiveMinimum": 0, "default": 2,
                            "description": "a length [m]"}}
  })";
  EXPECT_EQ(issues(schema, json::parse(R"({"a": 0})")),
            (Lines{"/a: must be > 0 [got] | a length [m]",
                   ": required key 'b' is missing | add \"b\": a length [m]"}));
  const SchemaChecker checker(schema);
  json v = json::object();
  checker.fill_defaults(v);
  EXPECT_EQ(v, json::parse(R"({"a": 2, "b": 2})"));
}

TEST(ScenarioSchemaCheck, DefaultsAreFilledIntoNestedObjectsButNotOverExistingValues) {
  const SchemaChecker checker(kObject);
  json v = json::parse(R"({"mass": 1, "mode": "fast", "count": 8})");
  checker.fill_defaults(v);
  EXPECT_EQ(v["count"], 8);
  EXPECT_EQ(v["inner"], json::parse(R"({"x": 1.5})"));
  json wrong = json::parse(R"({"inner": "not an object"})");
  checker.fill_defaults(wrong);  // only objects get keys
  EXPECT_EQ(wrong["inner"], "not an object");
}

TEST(ScenarioSchemaCheck, ArraysItemsAndFalseSchemas) {
  const char* schema = R"({"type": "array", "items": [{"type": "number"}, false]})";
  EXPECT_EQ(issues(schema, json::parse(R"([1, 2])")), (Lines{"/1: is not allowed here [got]"}));
  EXPECT_EQ(issues(R"({"type": "array", "items": {"type": "number", "exclusiveMinimum": 0}})",
                   json::parse("[1, -1, 2, 0]")),
            (Lines{"/1: must be > 0 [got]", "/3: must be > 0 [got]"}));
  EXPECT_EQ(issues(R"({"uniqueItems": true})", json::parse("[1, 2, 1]")),
            (Lines{": items must be unique: #0 and #2 are equal"}));
}

TEST(ScenarioSchemaCheck, StringRules) {
  EXPECT_EQ(issues(R"({"type": "string", "minLength": 1})", json("")),
            (Lines{": must not be empty"}));
  EXPECT_EQ(issues(R"({"type": "string", "maxLength": 2})", json("\xC3\xA9\xC3\xA9\xC3\xA9")),
            (Lines{": must be at most 2 characters long, got 3"}));
  EXPECT_EQ(issues(R"({"type": "string", "pattern": "^[a-z]+$"})", json("A")),
            (Lines{": must match the pattern \"^[a-z]+$\" [got]"}));
}

TEST(ScenarioSchemaCheck, BadSchemasAreRefusedUpFront) {
  EXPECT_THROW(SchemaChecker("{\"type\": "), SchemaError);
  EXPECT_THROW(SchemaChecker("[1, 2]"), SchemaError);
  EXPECT_THROW(SchemaChecker(R"({"properties": 3})"), SchemaError);
  EXPECT_NO_THROW(SchemaChecker("true"));
}

TEST(ScenarioSchemaCheck, LongStringsAreNotFedToRegularExpressions) {
  // libstdc++'s std::regex recurses per character: a 100 kB string overflows the stack.
  const std::string huge(100000, 'a');
  EXPECT_EQ(issues(R"({"type": "object", "properties": {"s": {"pattern": "^[a-z]+$"}}})",
                   json{{"s", huge}}),
            (Lines{"/s: is too long to be checked (more than 1000 characters where the schema "
                   "has patterns)"}));
  EXPECT_EQ(issues(R"({"type": "object", "patternProperties": {"^x": {"type": "number"}}})",
                   json{{huge, 1}})
                .size(),
            1u);
  const SchemaChecker checker(R"({"patternProperties": {"^x": {"default": 1}}})");
  json v = json{{huge, json::object()}};
  checker.fill_defaults(v);  // returns, without matching
  // Without patterns in the schema, long strings are fine.
  EXPECT_EQ(issues(R"({"type": "string", "maxLength": 5})", json(huge)),
            (Lines{": must be at most 5 characters long, got 100000"}));
}

TEST(ScenarioSchemaCheck, ABadRegexInASchemaIsAnIssueNotACrash) {
  const auto lines = issues(R"({"type": "string", "pattern": "(["})", json("x"));
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find("cannot be checked"), std::string::npos) << lines[0];
}

}  // namespace
}  // namespace rumble::scenario
