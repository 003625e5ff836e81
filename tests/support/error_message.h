// Test helper: the message of the exception a call throws, for tests that compare or search it.
#pragma once

#include <string>
#include <utility>

#include "skylight/core/error.h"

namespace skylight::testing_support {

// what() of the `E` that `f()` throws, or `none` when it returns normally; an exception of another
// type propagates (and fails the test).
template <class E = InvalidArgument, class F>
std::string error_message(F&& f, const std::string& none = "no error") {
  try {
    std::forward<F>(f)();
  } catch (const E& e) {
    return e.what();
  }
  return none;
}

}  // namespace skylight::testing_support
