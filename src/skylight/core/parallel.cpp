#include "skylight/core/parallel.h"

#include "skylight/core/numbers.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdlib>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace skylight {
namespace {

std::atomic<int> g_thread_override{0};
// ScopedThreadCount's count for the calling thread (0: none).
thread_local int t_thread_override = 0;

int default_thread_count() {
  if (const char* env = std::getenv("SKYLIGHT_THREADS"))
    if (const auto n = parse_thread_count(env)) return *n;
  // Read once: a system call of a few microseconds, which per-call users would pay each time.
  static const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return cores;
}

// Set while a thread runs chunks of a parallel_for: a nested call then runs serially instead of
// waiting on the pool it is part of.
thread_local bool t_in_parallel_region = false;

// One parallel_for call: chunks handed out by an atomic counter.
struct Job {
  const std::function<void(std::size_t, std::size_t)>* body = nullptr;
  std::size_t n = 0, grain = 1, chunks = 0;
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> done{0};
  std::exception_ptr error;
  std::mutex error_mutex;

  // Runs chunks until none is left; returns when this thread can take no more.
  void work() {
    const bool was = t_in_parallel_region;
    t_in_parallel_region = true;
    while (true) {
      const std::size_t c = next.fetch_add(1);
      if (c >= chunks) break;
      try {
        const std::size_t b = c * grain;
        (*body)(b, std::min(n, b + grain));
      } catch (...) {
        std::lock_guard lock(error_mutex);
        if (!error) error = std::current_exception();
      }
      done.fetch_add(1);
    }
    t_in_parallel_region = was;
  }
};

// Persistent workers (thread_count() - 1 of them; the caller is the last worker), so a
// sub-millisecond batch does not pay for starting threads.
class Pool {
 public:
  ~Pool() { resize(0); }

  void run(Job& job, std::size_t helpers) {
    std::unique_lock lock(mutex_);
    if (workers_.size() != helpers) {
      lock.unlock();
      resize(helpers);
      lock.lock();
    }
    job_ = &job;
    ++generation_;
    lock.unlock();
    wake_.notify_all();
    job.work();
    // Wait until every chunk has finished and no worker still holds the job.
    lock.lock();
    finished_.wait(lock, [&] { return job.done.load() == job.chunks && active_ == 0; });
    job_ = nullptr;
  }

 private:
  void resize(std::size_t count) {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    for (auto& t : workers_) t.join();
    workers_.clear();
    stop_ = false;
    // A new worker has seen the generation of its creation: a job posted right after (by run(),
    // before the thread got to read the generation itself) is still new to it.
    std::size_t now = 0;
    {
      std::lock_guard lock(mutex_);
      now = generation_;
    }
    for (std::size_t i = 0; i < count; ++i) workers_.emplace_back([this, now] { loop(now); });
  }

  void loop(std::size_t seen) {
    while (true) {
      Job* job = nullptr;
      {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
        if (stop_) return;
        seen = generation_;
        job = job_;
        if (!job) continue;
        ++active_;
      }
      job->work();
      {
        std::lock_guard lock(mutex_);
        --active_;
      }
      finished_.notify_all();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_, finished_;
  std::vector<std::thread> workers_;
  Job* job_ = nullptr;
  std::size_t generation_ = 0;
  int active_ = 0;
  bool stop_ = false;
};

Pool& pool() {
  static Pool p;
  return p;
}
std::mutex g_pool_mutex;  // one parallel_for at a time uses the pool; others wait

}  // namespace

std::optional<int> parse_thread_count(std::string_view text) {
  const auto v = parse_integer(text);
  if (v && *v >= 1 && *v <= kMaxThreads) return static_cast<int>(*v);
  return std::nullopt;
}

int thread_count() {
  if (t_thread_override > 0) return t_thread_override;
  const int o = g_thread_override.load();
  return o > 0 ? o : default_thread_count();
}

ScopedThreadCount::ScopedThreadCount(int n) : previous_(t_thread_override) {
  if (n > 0) t_thread_override = std::min(n, kMaxThreads);
}

ScopedThreadCount::~ScopedThreadCount() {
  t_thread_override = previous_;
}

void set_thread_count(int n) {
  g_thread_override.store(std::max(n, 0));
}

void parallel_for(std::size_t n, std::size_t grain,
                  const std::function<void(std::size_t, std::size_t)>& body) {
  if (n == 0) return;
  grain = std::max<std::size_t>(grain, 1);
  const std::size_t chunks = (n + grain - 1) / grain;
  const std::size_t workers =
      std::min<std::size_t>(static_cast<std::size_t>(thread_count()), chunks);
  if (workers <= 1 || t_in_parallel_region) {
    for (std::size_t b = 0; b < n; b += grain) body(b, std::min(n, b + grain));
    return;
  }
  Job job;
  job.body = &body;
  job.n = n;
  job.grain = grain;
  job.chunks = chunks;
  {
    std::lock_guard lock(g_pool_mutex);
    pool().run(job, static_cast<std::size_t>(thread_count()) - 1);
  }
  if (job.error) std::rethrow_exception(job.error);
}

}  // namespace skylight
