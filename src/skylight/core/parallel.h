// Threads over chunks: the one way skylight parallelises batch work.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string_view>

namespace skylight {

// Thread counts accepted from set_thread_count, SKYLIGHT_THREADS and the CLI's --threads.
inline constexpr int kMaxThreads = 1024;

// Number of worker threads batch helpers use: set_thread_count(n) (n >= 1), else the environment
// variable SKYLIGHT_THREADS if it is an integer in [1, kMaxThreads], else
// std::thread::hardware_concurrency().
int thread_count();
// A thread count as text (SKYLIGHT_THREADS, --threads): an integer in [1, kMaxThreads], else
// nullopt. The library ignores an invalid SKYLIGHT_THREADS; the CLI refuses it.
std::optional<int> parse_thread_count(std::string_view text);
// n >= 1; 0 restores the default.
void set_thread_count(int n);

// thread_count() is `n` for the calling thread while this lives (n >= 1; 0 changes nothing):
// a per-call count (the Python package's threads=) that neither changes nor races with the
// process-wide one. Scopes nest.
class ScopedThreadCount {
 public:
  explicit ScopedThreadCount(int n);
  ~ScopedThreadCount();
  ScopedThreadCount(const ScopedThreadCount&) = delete;
  ScopedThreadCount& operator=(const ScopedThreadCount&) = delete;

 private:
  int previous_;
};

// Calls body(begin, end) over [0, n) in chunks of at most `grain` items, on up to thread_count()
// threads: the calling thread plus a persistent pool of thread_count() - 1 workers (started on
// first use, resized when the count changes), so a call costs ~0.4 us instead of a thread start.
// Chunks are handed out dynamically. The first exception thrown by body is rethrown on the calling
// thread after all chunks have run. A parallel_for called from inside a body runs serially;
// concurrent calls from different threads take turns on the pool.
void parallel_for(std::size_t n, std::size_t grain,
                  const std::function<void(std::size_t begin, std::size_t end)>& body);

}  // namespace skylight
