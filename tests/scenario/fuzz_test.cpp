// Robustness: load_document + validate + print_diagnostics on mangled input must return (never
// crash, hang or throw), and whatever is invalid must say so. Fixed seeds: failures reproduce.
#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "scenario/scenario.hpp"
#include "test_support.hpp"

namespace rumble::scenario {
namespace {

using nlohmann::json;

std::string minimal_text() {
  return test::read_file(test::scenario_test_dir() / "valid" / "minimal.json");
}

/// Runs the whole pipeline on `text`; returns the diagnostics. Checks what holds for any input:
/// a document that does not load has diagnostics, every diagnostic has a message, positions lie
/// inside the text, and both output formats work (the JSON one parses back).
std::vector<Diagnostic> run(const std::string& text) {
  std::vector<Diagnostic> diags;
  auto doc = parse_document("fuzz.json", text, diags);
  if (doc) {
    diags = validate(*doc, test::golden_registry());
  } else {
    EXPECT_FALSE(diags.empty());
  }
  const std::size_t lines =
      static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) + 1;
  for (const Diagnostic& d : diags) {
    EXPECT_FALSE(d.message.empty());
    EXPECT_LE(d.line, lines);
  }
  std::ostringstream os;
  print_diagnostics(os, doc ? &*doc : nullptr, "fuzz.json", diags, Format::kText);
  std::ostringstream js;
  print_diagnostics(js, doc ? &*doc : nullptr, "fuzz.json", diags, Format::kJson);
  const auto parses = [](const std::string& out) {
    try {
      return !json::parse(out).is_discarded();
    } catch (const std::exception&) {
      return false;
    }
  };
  EXPECT_TRUE(parses(js.str())) << js.str();
  return diags;
}

TEST(ScenarioFuzz, EveryTruncationIsReported) {
  const std::string text = minimal_text();
  // Every proper prefix that still holds the opening '{' lacks its closing '}': never valid.
  for (std::size_t n = 0; n < text.rfind('}'); ++n) {
    const auto diags = run(text.substr(0, n));
    ASSERT_FALSE(diags.empty()) << "prefix of " << n << " bytes";
  }
}

TEST(ScenarioFuzz, RandomByteChangesNeverCrash) {
  const std::string text = minimal_text();
  std::mt19937 rng(20261123);
  std::uniform_int_distribution<std::size_t> where(0, text.size() - 1);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<int> how_many(1, 4);
  for (int i = 0; i < 1500; ++i) {
    std::string mutated = text;
    for (int k = how_many(rng); k > 0; --k) mutated[where(rng)] = static_cast<char>(byte(rng));
    run(mutated);
  }
}

TEST(ScenarioFuzz, RandomGarbageIsRefused) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<std::size_t> length(1, 4096);
  for (int i = 0; i < 300; ++i) {
    std::string garbage(length(rng), '\0');
    for (char& c : garbage) c = static_cast<char>(byte(rng));
    EXPECT_FALSE(run(garbage).empty());
  }
  // Valid JSON that is no scenario at all.
  for (const char* text : {"[]", "null", "3", "\"x\"", "{}", "[[[[[]]]]]", "{\"\": {\"\": []}}"}) {
    EXPECT_FALSE(run(text).empty()) << text;
  }
}

TEST(ScenarioFuzz, DeepNestingIsRefusedWithoutOverflowingTheStack) {
  const std::size_t depth = 10000;
  const std::string arrays = std::string(depth, '[') + std::string(depth, ']');
  std::string objects;
  for (std::size_t i = 0; i < depth; ++i) objects += "{\"a\":";
  objects += "1" + std::string(depth, '}');
  for (const std::string& text : {arrays, objects, std::string(depth, '[')}) {
    const auto diags = run(text);
    ASSERT_EQ(diags.size(), 1u);
    EXPECT_EQ(diags[0].message.rfind("nesting is too deep", 0), 0u) << diags[0].message;
  }
}

TEST(ScenarioFuzz, InputsOverTheSizeLimitAreRefused) {
  std::string big = "{\"description\": \"" + std::string(70u << 20, 'x') + "\"}";
  const auto diags = run(big);
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].message, "file is too large (70.0 MiB; the limit is 64 MiB)");
}

TEST(ScenarioFuzz, ExtremeNumbersAreReportedNotMisread) {
  const json base = json::parse(minimal_text());
  const auto with = [&](const std::string& number) {
    std::string text = base.dump(2);
    const std::string key = "\"end\": 0.05";
    text.replace(text.find(key), key.size(), "\"end\": " + number);
    return run(text);
  };
  auto diags = with("1e400");
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].message, "number 1e400 is too large (the largest double is about 1.8e308)");
  EXPECT_GT(diags[0].line, 0u);
  EXPECT_EQ(with("-1e400").size(), 1u);
  // Underflows to 0, which the rule rejects, quoting the number as written.
  bool found = false;
  for (const Diagnostic& d : with("1e-400")) {
    if (d.pointer == "/time/end") {
      found = true;
      EXPECT_EQ(d.message, "must be in [1e-06, 3600], got 1e-400");
    }
  }
  EXPECT_TRUE(found);
  for (const char* n : {"123456789012345678901234567890", "-0", "1e308", "0.0000000000000000001"}) {
    run(std::string(with(n).empty() ? "" : "x"));  // must simply return
  }
}

TEST(ScenarioFuzz, EveryValueReplacedByEveryKindOfValue) {
  // Walk every pointer of the minimal scenario and put each kind of value there.
  const json base = json::parse(minimal_text());
  const json replacements =
      json::parse(R"([null, true, -1, 0, 2.5, 1e308, "", "x", [], [1, "a"], {}, {"zz": 1}])");
  std::vector<json::json_pointer> pointers;
  const json flat = base.flatten();
  for (const auto& [path, value] : flat.items()) {
    json::json_pointer p(path);
    while (!p.empty()) {
      pointers.push_back(p);
      p = p.parent_pointer();
    }
  }
  std::sort(pointers.begin(), pointers.end(),
            [](const auto& a, const auto& b) { return a.to_string() < b.to_string(); });
  pointers.erase(std::unique(pointers.begin(), pointers.end()), pointers.end());
  for (const auto& p : pointers) {
    for (const json& r : replacements) {
      json j = base;
      j[p] = r;
      run(j.dump());
    }
  }
}

TEST(ScenarioFuzz, InvalidUtf8AndControlCharactersInKeysAndStrings) {
  for (const std::string& text :
       {std::string("{\"na\xC3me\": 1}"), std::string("{\"name\": \"a\x01b\"}"),
        std::string("{\"\xED\xA0\x80\": 1}"), std::string("{\"a\\u0000b\": 1}"),
        std::string("{\"a\\nb\": {\"\\t\": 1}}", 20), std::string("{\"a\": \"\0\"}", 10)}) {
    EXPECT_FALSE(run(text).empty());
  }
}

}  // namespace
}  // namespace rumble::scenario
