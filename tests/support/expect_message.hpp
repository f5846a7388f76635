// EXPECT that a call throws std::invalid_argument with exactly the given text, or with a text
// that contains each of the given parts (for messages that quote computed numbers).
#pragma once

#include <gtest/gtest.h>

#include <initializer_list>
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

template <class F>
void expect_invalid_argument_containing(F&& call, std::initializer_list<std::string> parts) {
  try {
    call();
    ADD_FAILURE() << "no exception; expected one containing: " << *parts.begin();
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    for (const std::string& part : parts)
      EXPECT_NE(what.find(part), std::string::npos) << "'" << part << "' not in: " << what;
  }
}

}  // namespace rumble::test
