// The message of the exception a call throws, for the post-processing tests.
#pragma once

#include <exception>
#include <string>

namespace rumble::post {

/// What `call()` throws (its what()), or "(no exception)".
std::string message_of(auto&& call) {
  try {
    call();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no exception)";
}

}  // namespace rumble::post
