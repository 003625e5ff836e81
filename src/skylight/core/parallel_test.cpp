#include "skylight/core/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include "skylight/core/error.h"

namespace skylight {
namespace {

TEST(Parallel, CoversEveryIndexOnce) {
  for (int threads : {1, 2, 3}) {
    set_thread_count(threads);
    std::vector<std::atomic<int>> hits(10007);
    parallel_for(hits.size(), 64, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) hits[i]++;
    });
    for (std::size_t i = 0; i < hits.size(); ++i) ASSERT_EQ(hits[i].load(), 1) << i;
  }
  set_thread_count(0);
}

TEST(Parallel, PropagatesExceptions) {
  set_thread_count(2);
  EXPECT_THROW(parallel_for(1000, 10,
                            [](std::size_t b, std::size_t) {
                              if (b == 500) throw IoError("boom");
                            }),
               IoError);
  set_thread_count(0);
}

TEST(Parallel, TheFirstCallAfterAResizeUsesTheWorkers) {
  // A worker started by the resize must take part in the very job that caused it (it once waited
  // for the next job when it started after the job was posted).
  for (const int threads : {2, 3}) {
    set_thread_count(threads);
    std::mutex m;
    std::set<std::thread::id> seen;
    parallel_for(40, 1, [&](std::size_t, std::size_t) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      const std::lock_guard lock(m);
      seen.insert(std::this_thread::get_id());
    });
    EXPECT_GE(seen.size(), 2u) << threads;
  }
  set_thread_count(0);
}

TEST(Parallel, ScopedThreadCountIsPerThreadAndNests) {
  set_thread_count(3);
  {
    const ScopedThreadCount one(1);
    EXPECT_EQ(thread_count(), 1);
    {
      const ScopedThreadCount two(2);
      EXPECT_EQ(thread_count(), 2);
      // Another thread keeps the process-wide count.
      int other = 0;
      std::thread([&] { other = thread_count(); }).join();
      EXPECT_EQ(other, 3);
      // The scoped count is the count a parallel_for of this thread takes.
      std::atomic<int> chunks{0};
      parallel_for(1000, 10, [&](std::size_t, std::size_t) { chunks++; });
      EXPECT_EQ(chunks.load(), 100);
    }
    EXPECT_EQ(thread_count(), 1);
    const ScopedThreadCount none(0);  // changes nothing
    EXPECT_EQ(thread_count(), 1);
  }
  EXPECT_EQ(thread_count(), 3);
  set_thread_count(0);
}

}  // namespace
}  // namespace skylight
