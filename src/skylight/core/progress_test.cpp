#include "skylight/core/progress.h"

#include <gtest/gtest.h>

#include <string>
#include <thread>
#include <vector>

namespace skylight {
namespace {

TEST(Progress, StepsGoToTheCallingThreadsSinkAndTheOneBeforeReturns) {
  std::vector<std::string> outer, inner;
  report_progress(0, 1, "nobody listens");  // no sink: nothing happens
  {
    const ScopedProgressSink a([&](int d, int t, std::string_view s) {
      outer.push_back(std::to_string(d) + "/" + std::to_string(t) + " " + std::string(s));
    });
    report_progress(1, 3, "first");
    {
      const ScopedProgressSink b([&](int, int, std::string_view s) { inner.emplace_back(s); });
      report_progress(2, 3, "second");
      // Another thread has its own (none).
      std::thread([] { report_progress(9, 9, "elsewhere"); }).join();
    }
    report_progress(3, 3, "third");
  }
  report_progress(4, 4, "after");
  EXPECT_EQ(outer, (std::vector<std::string>{"1/3 first", "3/3 third"}));
  EXPECT_EQ(inner, (std::vector<std::string>{"second"}));
}

}  // namespace
}  // namespace skylight
