// EXPECT that a call throws std::invalid_argument with exactly the given text.
#pragma once

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace rumble::test {

template <class F>
void expect_invalid_argument(F&& call, const std::string& text) {
  try {
    call();
    ADD_FAILURE() << "no exception; expected: " << text;
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(e.what(), text);
  }
}

}  // namespace rumble::test
