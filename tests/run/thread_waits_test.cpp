// rumble's choice of OpenMP waiting for its plugins (core/thread_waits.hpp): PASSIVE when the user
// chose nothing, and the user's choice untouched otherwise (docs/toolchain.md section 8).
#include "core/thread_waits.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace rumble {
namespace {

/// The two variables as they were, put back at the end of each test.
class ThreadWaits : public ::testing::Test {
 protected:
  void SetUp() override {
    for (int i = 0; i < 2; ++i)
      if (const char* v = std::getenv(kNames[i])) saved_[i] = v, had_[i] = true;
    ::unsetenv("OMP_WAIT_POLICY");
    ::unsetenv("GOMP_SPINCOUNT");
  }
  void TearDown() override {
    for (int i = 0; i < 2; ++i)
      had_[i] ? ::setenv(kNames[i], saved_[i].c_str(), 1) : ::unsetenv(kNames[i]);
  }
  static std::string policy() {
    const char* v = std::getenv("OMP_WAIT_POLICY");
    return v != nullptr ? v : "(unset)";
  }

 private:
  static constexpr const char* kNames[2] = {"OMP_WAIT_POLICY", "GOMP_SPINCOUNT"};
  std::string saved_[2];
  bool had_[2] = {false, false};
};

TEST_F(ThreadWaits, NoChoiceOfTheUsersIsPassive) {
  EXPECT_TRUE(prefer_passive_thread_waits());
  EXPECT_EQ(policy(), "PASSIVE");
}

TEST_F(ThreadWaits, TheUsersPolicyOrSpinCountStands) {
  ::setenv("OMP_WAIT_POLICY", "ACTIVE", 1);
  EXPECT_FALSE(prefer_passive_thread_waits());
  EXPECT_EQ(policy(), "ACTIVE");
  ::unsetenv("OMP_WAIT_POLICY");
  ::setenv("GOMP_SPINCOUNT", "300000", 1);
  EXPECT_FALSE(prefer_passive_thread_waits());
  EXPECT_EQ(policy(), "(unset)") << "a spin count is a choice of waiting too";
}

}  // namespace
}  // namespace rumble
