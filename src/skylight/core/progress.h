// Progress of a long computation that the library runs on its caller's behalf (a model's
// precomputed tables, built in its constructor): the steps go to the calling thread's sink, which
// an application sets around its work (the CLI: its progress line on a terminal). With no sink set
// nothing is reported; the library itself never prints.
#pragma once

#include <functional>
#include <string_view>

namespace skylight {

using ProgressSink = std::function<void(int done, int total, std::string_view step)>;

// Sets the calling thread's sink for its lifetime (the one before is restored).
class ScopedProgressSink {
 public:
  explicit ScopedProgressSink(ProgressSink sink);
  ~ScopedProgressSink();
  ScopedProgressSink(const ScopedProgressSink&) = delete;
  ScopedProgressSink& operator=(const ScopedProgressSink&) = delete;

 private:
  ProgressSink previous_;
};

// Step `done` of `total` of the calling thread's computation (done == total: finished).
void report_progress(int done, int total, std::string_view step);

}  // namespace skylight
