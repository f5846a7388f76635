#include "scenario/document.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "test_support.hpp"

namespace rumble::scenario {
namespace {

namespace fs = std::filesystem;

// "line:col: message | hint" of the single diagnostic parse_document gives for `text`.
std::string parse_failure(const std::string& text) {
  std::vector<Diagnostic> diags;
  const auto doc = parse_document("x.json", text, diags);
  if (doc) return "parsed";
  if (diags.size() != 1) return "expected one diagnostic, got " + std::to_string(diags.size());
  const Diagnostic& d = diags[0];
  return std::to_string(d.line) + ":" + std::to_string(d.column) + ": " + d.message + " | " +
         d.hint;
}

struct SyntaxCase {
  const char* text;
  const char* expected;
};

class SyntaxErrors : public ::testing::TestWithParam<SyntaxCase> {};

TEST_P(SyntaxErrors, AreDescribedInPlainWordsAtTheRightPlace) {
  EXPECT_EQ(parse_failure(GetParam().text), GetParam().expected) << "text: " << GetParam().text;
}

INSTANTIATE_TEST_SUITE_P(
    Scenario, SyntaxErrors,
    ::testing::Values(
        SyntaxCase{"{\n  \"a\": 1,\n}",
                   "2:9: syntax error: trailing comma after the last member of an object | "
                   "remove this comma; JSON allows no comma before '}'"},
        SyntaxCase{"{\"a\": [1, 2, ]}",
                   "1:12: syntax error: trailing comma after the last element of an array | "
                   "remove this comma; JSON allows no comma before ']'"},
        SyntaxCase{"{\"a\": \"abc}",
                   "1:7: syntax error: string is missing its closing quote | end the string "
                   "with \" on the same line"},
        SyntaxCase{"{\"a\": \"abc\n}",
                   "1:7: syntax error: line break inside a string | close the string with \" "
                   "before the end of the line, or write the break as \\n"},
        SyntaxCase{"{a: 1}",
                   "1:2: syntax error: object key a must be in double quotes | write \"a\""},
        SyntaxCase{"{'a': 1}",
                   "1:2: syntax error: strings must be in double quotes, not single quotes | "
                   "replace ' with \""},
        SyntaxCase{"{\"a\": 1\n \"b\": 2}",
                   "2:2: syntax error: missing ',' between object members | add a comma after "
                   "the previous value"},
        SyntaxCase{"[1 2]",
                   "1:4: syntax error: missing ',' between array elements | add a comma after "
                   "the previous element"},
        SyntaxCase{"{\"a\" 1}",
                   "1:6: syntax error: missing ':' after the object key | write "
                   "\"key\": value"},
        SyntaxCase{"{\"a\": 01}",
                   "1:7: syntax error: numbers must not have leading zeros | "
                   "write 1 (or 0.1)"},
        // Found by the fuzz target (tests/fuzz/regressions/scenario/all_zero_number.json): only
        // zeros left nothing to suggest, and an std::out_of_range escaped instead of a diagnostic.
        SyntaxCase{"{\"a\": 00}",
                   "1:7: syntax error: numbers must not have leading zeros | "
                   "write 0 (or 0.0)"},
        SyntaxCase{"{\"a\": -000}",
                   "1:7: syntax error: numbers must not have leading zeros | "
                   "write -0 (or -0.0)"},
        SyntaxCase{"{\"a\": 1.}",
                   "1:7: syntax error: invalid number '1.': expected digit after "
                   "'.' | numbers look like 12, -0.5 or 2.1e11"},
        SyntaxCase{"{\"a\": NaN}",
                   "1:7: syntax error: 'NaN' is not a JSON number | JSON has no "
                   "NaN or Infinity; use a finite number"},
        SyntaxCase{"{\"a\": True}",
                   "1:7: syntax error: invalid literal 'True' | did you mean "
                   "true? JSON literals are lowercase: true, false, null"},
        SyntaxCase{"{\"a\": fast}",
                   "1:7: syntax error: unquoted text 'fast' | strings must be "
                   "in double quotes: \"fast\""},
        SyntaxCase{"{\"a\": 1} x",
                   "1:10: syntax error: unexpected text after the end of the JSON "
                   "value | a scenario file holds exactly one JSON object; is "
                   "there an extra '}' or a missing '{'?"},
        SyntaxCase{"{\"a\": 1}}",
                   "1:9: syntax error: unexpected text after the end of the JSON "
                   "value | a scenario file holds exactly one JSON object; is "
                   "there an extra '}' or a missing '{'?"},
        SyntaxCase{"{\"a\": \"\xFF\"}",
                   "1:8: syntax error: invalid UTF-8 byte 0xFF in a string | "
                   "save the file as UTF-8"},
        SyntaxCase{"{\n  \"a\": [1,\n",
                   "2:11: syntax error: unexpected end of file: the '[' at "
                   "line 2, column 8 is never closed | the file may be "
                   "truncated; add the missing ']'"},
        SyntaxCase{"// note\n{}",
                   "1:1: syntax error: comments are not allowed in JSON | remove "
                   "the comment; free text can go in the \"description\" key"},
        SyntaxCase{"{\"a\": \"\\q\"}",
                   "1:8: syntax error: invalid escape sequence '\\q' in a "
                   "string | valid escapes are \\\" \\\\ \\/ \\b \\f \\n \\r "
                   "\\t \\uXXXX; write a backslash as \\\\"},
        SyntaxCase{"{\"a\": }",
                   "1:7: syntax error: missing value before '}' | write a value: a "
                   "number, a string in double quotes, true, false, null, an object "
                   "or an array"},
        SyntaxCase{"{\"a\": 1e400}",
                   "1:7: number 1e400 is too large (the largest double is "
                   "about 1.8e308) | check the exponent"},
        SyntaxCase{"\x7F\x45\x4C\x46\x02",
                   "1:1: syntax error: unexpected character 0x7F | is "
                   "this a JSON text file? (it may be binary, or not "
                   "saved as UTF-8)"}));

TEST(ScenarioDocument, ParsesValidTextAndKeepsItForPositions) {
  std::vector<Diagnostic> diags;
  const auto doc = parse_document("x.json", "\xEF\xBB\xBF{\"a\": [1, 2.5]}", diags);
  ASSERT_TRUE(doc.has_value());
  EXPECT_TRUE(diags.empty());
  EXPECT_EQ(doc->json["a"][1], 2.5);
  EXPECT_EQ(doc->path, "x.json");
  EXPECT_EQ(doc->text.size(), 18u);
}

// nlohmann keeps the last of a repeated key: the first value would be dropped without a word.
TEST(ScenarioDocument, DuplicateKeysAreRefusedWithBothPlaces) {
  EXPECT_EQ(parse_failure("{\"time\": {\"end\": 1.2,\n  \"end\": 0.5}}"),
            "2:3: duplicate key \"end\" (first at line 1, column 11); JSON keeps only the last "
            "value and would drop the other without a word | keep one of the two");
  std::vector<Diagnostic> diags;
  EXPECT_FALSE(
      parse_document("x.json", R"({"a": 1, "b": [{"c": 1, "c": 2}], "a": 3, "a": 4})", diags));
  ASSERT_EQ(diags.size(), 3u);
  EXPECT_EQ(diags[0].pointer, "/b/0/c");
  EXPECT_EQ(diags[1].pointer, "/a");
  EXPECT_EQ(diags[1].column, 35u);
  EXPECT_EQ(diags[2].pointer, "/a");
  EXPECT_EQ(diags[2].column, 43u);
  EXPECT_NE(diags[2].message.find("(first at line 1, column 35)"), std::string::npos)
      << diags[2].message;
  // The same key in sibling objects, or escaped differently but equal, is (not) a repeat.
  diags.clear();
  EXPECT_TRUE(parse_document("x.json", R"({"a": {"k": 1}, "b": {"k": 1}})", diags));
  EXPECT_FALSE(parse_document("x.json", R"({"k": 1, "\u006b": 2})", diags));
}

TEST(ScenarioDocument, EmptyAndBlankFilesAreRefused) {
  EXPECT_EQ(parse_failure(""), "0:0: file is empty | a scenario is one JSON object: { ... }");
  EXPECT_EQ(parse_failure(" \n\t\r\n"),
            "0:0: file is empty | a scenario is one JSON object: { ... }");
}

TEST(ScenarioDocument, NestingDeeperThanTheLimitIsRefusedWhereItGoesTooDeep) {
  const std::string ok = std::string(kMaxNestingDepth, '[') + std::string(kMaxNestingDepth, ']');
  std::vector<Diagnostic> diags;
  EXPECT_TRUE(parse_document("x.json", ok, diags).has_value());
  const std::string deep = "{\"a\":" + std::string(kMaxNestingDepth, '[');
  EXPECT_EQ(parse_failure(deep),
            "1:261: nesting is too deep (more than 256 levels of arrays and objects) | a scenario "
            "needs only a few levels; is this the right file?");
}

TEST(ScenarioDocument, MissingFileDirectoryAndUnreadableFileAreReported) {
  std::vector<Diagnostic> diags;
  EXPECT_FALSE(load_document("/nonexistent/dir/x.json", diags).has_value());
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].message, "file not found");
  EXPECT_EQ(diags[0].line, 0u);

  diags.clear();
  EXPECT_FALSE(load_document(fs::temp_directory_path(), diags).has_value());
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].message, "is a directory, not a scenario file");
}

// A FIFO on disk waited for a writer for ever (a scenario or a study file; issue #30 item 3) and
// a device was read up to the size limit: both are refused unopened. What the process was given
// on standard input stays readable (tests/cli: `rumble run /dev/stdin`).
TEST(ScenarioDocument, AFifoOrADeviceIsRefusedUnopened) {
  const fs::path fifo = fs::temp_directory_path() / "rumble_scenario_test_fifo.json";
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (const fs::path& p : {fifo, fs::path("/dev/zero")}) {
    std::vector<Diagnostic> diags;
    EXPECT_FALSE(load_document(p, diags).has_value());
    ASSERT_EQ(diags.size(), 1u);
    EXPECT_EQ(diags[0].message, p == fifo ? "is a FIFO (named pipe), not a regular file"
                                          : "is a device, not a regular file");
    EXPECT_EQ(diags[0].hint, "give the file itself, or pass it on standard input as /dev/stdin");
  }
  fs::remove(fifo);
}

TEST(ScenarioDocument, LoadsAFileFromDisk) {
  std::vector<Diagnostic> diags;
  const auto doc = load_document(test::scenario_test_dir() / "valid" / "minimal.json", diags);
  ASSERT_TRUE(doc.has_value()) << (diags.empty() ? "" : diags[0].message);
  EXPECT_EQ(doc->json["schema_version"], 1);
}

TEST(ScenarioDocument, FilesOverTheSizeLimitAreRefusedBeforeReading) {
  const fs::path big = fs::temp_directory_path() / "rumble_scenario_test_big.json";
  {
    std::ofstream out(big, std::ios::binary);
    out << "{}";
  }
  fs::resize_file(big, kMaxDocumentBytes + 1);  // sparse: costs no disk
  std::vector<Diagnostic> diags;
  EXPECT_FALSE(load_document(big, diags).has_value());
  fs::remove(big);
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].message, "file is too large (67108865 bytes; the limit is 64 MiB)");
}

}  // namespace
}  // namespace rumble::scenario
