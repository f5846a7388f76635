// --set POINTER=VALUE: parsing, setting by JSON pointer (RFC 6901), and every message.
#include "scenario/overrides.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/errors.hpp"

namespace rumble::scenario {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

std::string parse_error(const std::string& text) {
  try {
    parse_set_option(text);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

std::string apply_error(json doc, const std::string& text) {
  try {
    Override o = parse_set_option(text);
    apply_override(doc, o);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SetOption, ValuesAreJsonOrBareWords) {
  EXPECT_EQ(parse_set_option("/soil/params/E=1e7").value, json(1e7));
  EXPECT_EQ(parse_set_option("/a=true").value, json(true));
  EXPECT_EQ(parse_set_option("/a=null").value, json(nullptr));
  EXPECT_EQ(parse_set_option("/coupling/type=jacobi").value, json("jacobi"));
  EXPECT_EQ(parse_set_option("/coupling/type=\"jacobi\"").value, json("jacobi"));
  EXPECT_EQ(parse_set_option("/soil/params={\"k\": 1}").value, json({{"k", 1}}));
  EXPECT_EQ(parse_set_option("/outputs/receivers=[2.5, 5]").value, json({2.5, 5}));
  EXPECT_EQ(parse_set_option("/name=a=b").value, json("a=b"));  // the first '=' splits
  EXPECT_EQ(parse_set_option("/soil/params/E=1e7").pointer, "/soil/params/E");
  EXPECT_EQ(parse_set_option("/a~1b=1").pointer, "/a~1b");
}

TEST(SetOption, Messages) {
  EXPECT_EQ(parse_error("soil/params/E"),
            "--set soil/params/E: expected POINTER=VALUE, e.g. --set /soil/params/E=1.55e8 or "
            "--set /coupling/type=jacobi");
  EXPECT_EQ(parse_error("=5"),
            "--set =5: the pointer is empty; name the value to replace, e.g. /soil/params/E (the "
            "whole scenario cannot be replaced)");
  EXPECT_EQ(parse_error("soil/E=5"),
            "--set soil/E=5: \"soil/E\" is not a JSON pointer: it starts with '/', e.g. "
            "/soil/params/E");
  EXPECT_EQ(parse_error("/a~2=5"),
            "--set /a~2=5: \"/a~2\" is not a JSON pointer: '~' must be followed by 0 (for '~') "
            "or 1 (for '/')");
  EXPECT_EQ(parse_error("/name="),
            "--set /name=: no value after '='; write a JSON value, e.g. /name=1.5, or "
            "'/name=\"\"' for an empty string");
  EXPECT_THAT(parse_error("/soil/params={\"k\": "),
              HasSubstr("--set /soil/params={\"k\": : the value is not valid JSON (parse error"));
  EXPECT_THAT(parse_error("/soil/params={\"k\": "),
              HasSubstr("; quote the whole option for the shell, e.g. --set '/soil/params={\"k\": "
                        "1e8}'"));
}

// Invalid UTF-8 used to pass as a bare word and end the run in the JSON library's exception
// when summary.json was written (issue #30 item 3); it is refused where it came in, and the
// message itself is valid UTF-8 (the bad bytes shown as U+FFFD).
TEST(SetOption, BytesThatAreNotUtf8AreRefusedWithTheirOffset) {
  EXPECT_EQ(parse_error("/name=\xff\xfe"),
            "--set \"/name=\xEF\xBF\xBD\xEF\xBF\xBD\": byte 0xFF at offset 6 is not UTF-8, and a "
            "scenario is UTF-8 text (RFC 8259); write the value in UTF-8, or as a JSON string "
            "with \\u escapes, e.g. --set '/name=\"caf\\u00e9\"'");
  EXPECT_THAT(parse_error("/na\xc3me=1"), HasSubstr("byte 0xC3 at offset 3 is not UTF-8"));
  EXPECT_THAT(parse_error("/name=\xc0\xaf"), HasSubstr("byte 0xC0 at offset 6"));      // overlong
  EXPECT_THAT(parse_error("/name=\xed\xa0\x80"), HasSubstr("byte 0xED at offset 6"));  // surrogate
  EXPECT_THAT(parse_error("/name=\xf4\x90\x80\x80"), HasSubstr("byte 0xF4 at offset 6"));
  EXPECT_THAT(parse_error("/name=caf\xc3"), HasSubstr("byte 0xC3 at offset 9"));  // cut short
  // Well-formed text of every length passes.
  EXPECT_EQ(parse_set_option("/name=caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x9a\x86").value,
            json("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x9a\x86"));
}

TEST(ApplyOverride, ReplacesAndCreatesMembers) {
  json doc = {{"soil", {{"type", "winkler"}, {"params", {{"k", 1}}}}}, {"v", {{{"s", 1}}}}};
  Override o = parse_set_option("/soil/params/k=2");
  apply_override(doc, o);
  EXPECT_EQ(doc["soil"]["params"]["k"], 2);
  EXPECT_EQ(o.applied_at, "/soil/params/k");
  Override created = parse_set_option("/soil/extra/deep/x=3");
  apply_override(doc, created);
  EXPECT_EQ(doc["soil"]["extra"]["deep"]["x"], 3);
  EXPECT_EQ(created.applied_at, "/soil/extra");
  Override element = parse_set_option("/v/0/s=5");
  apply_override(doc, element);
  EXPECT_EQ(doc["v"][0]["s"], 5);
  Override escaped = parse_set_option("/a~1b~0c=1");
  apply_override(doc, escaped);
  EXPECT_EQ(doc["a/b~c"], 1);
}

TEST(ApplyOverride, Messages) {
  const json doc = {
      {"soil", {{"type", "winkler"}}}, {"vehicles", {{{"speed", 20}}}}, {"flag", true}};
  EXPECT_EQ(apply_error(doc, "/vehicles/3/speed=30"),
            "--set /vehicles/3/speed=30: /vehicles is an array (it has 1 element, index 0), which "
            "has no element \"3\"; an override replaces an element but does not add one: add it "
            "in the scenario file");
  EXPECT_EQ(apply_error(doc, "/vehicles/-=1"),
            "--set /vehicles/-=1: /vehicles is an array (it has 1 element, index 0), which has no "
            "element \"-\"; an override replaces an element but does not add one: add it in the "
            "scenario file");
  EXPECT_EQ(apply_error(doc, "/vehicles/first/speed=30"),
            "--set /vehicles/first/speed=30: /vehicles is an array (it has 1 element, index 0), "
            "which has no element \"first\"; name an element by its index, e.g. /vehicles/0");
  EXPECT_EQ(apply_error(doc, "/vehicles/01/speed=30"),
            "--set /vehicles/01/speed=30: /vehicles is an array (it has 1 element, index 0), "
            "which has no element \"01\"; name an element by its index, e.g. /vehicles/0");
  EXPECT_EQ(apply_error(doc, "/soil/type/x=1"),
            "--set /soil/type/x=1: /soil/type is a string, not an object or array, so it has no "
            "member \"x\"; set /soil/type itself, or correct the pointer");
  EXPECT_EQ(apply_error(doc, "/flag/x=1"),
            "--set /flag/x=1: /flag is a boolean, not an object or array, so it has no member "
            "\"x\"; set /flag itself, or correct the pointer");
}

TEST(OverrideNote, OnlyAtOrBelowWhatWasSet) {
  json doc = {{"soil", {{"params", {{"E", 1}}}}}};
  std::vector<Override> set{parse_set_option("/soil/params/E=-1"),
                            parse_set_option("/soil/parms/E=2")};
  for (Override& o : set) apply_override(doc, o);
  EXPECT_EQ(override_note(set, "/soil/params/E"), " (set by --set)");
  EXPECT_EQ(override_note(set, "/soil/parms"), " (set by --set)");  // created by it
  EXPECT_EQ(override_note(set, "/soil/params"), "");
  EXPECT_EQ(override_note(set, "/soil/params/Ex"), "");
  EXPECT_EQ(override_note(set, ""), "");
  EXPECT_EQ(override_text(set[0]), "/soil/params/E=-1");
}

}  // namespace
}  // namespace rumble::scenario
