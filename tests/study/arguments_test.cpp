// cli/arguments: repeated valued options (--set) beside the single-valued ones.
#include "cli/arguments.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace rumble::cli {
namespace {

using ::testing::ElementsAre;

TEST(Arguments, RepeatedOptionsKeepEveryValueInOrder) {
  const Arguments a({"f.json", "--set", "/a=1", "--output", "x", "--set=/b=2", "--output=y"},
                    {"force"}, {"output"}, {"set"});
  EXPECT_THAT(a.positional(), ElementsAre("f.json"));
  EXPECT_THAT(a.values("set"), ElementsAre("/a=1", "/b=2"));
  EXPECT_EQ(a.value("output"), "y");  // a single-valued option: the last one counts
  EXPECT_TRUE(a.values("other").empty());
}

TEST(Arguments, Messages) {
  try {
    Arguments({"--set"}, {}, {}, {"set"});
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(), "option --set needs a value");
  }
  try {
    Arguments({"--sett=1"}, {"force"}, {"jobs"}, {"set"});
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(), "unknown option '--sett=1'; options here: --force, --jobs, --set");
  }
}

}  // namespace
}  // namespace rumble::cli
