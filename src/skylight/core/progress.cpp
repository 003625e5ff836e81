#include "skylight/core/progress.h"

#include <utility>

namespace skylight {

namespace {
thread_local ProgressSink current_sink;
}  // namespace

ScopedProgressSink::ScopedProgressSink(ProgressSink sink)
    : previous_(std::exchange(current_sink, std::move(sink))) {}

ScopedProgressSink::~ScopedProgressSink() {
  current_sink = std::move(previous_);
}

void report_progress(int done, int total, std::string_view step) {
  if (current_sink) current_sink(done, total, step);
}

}  // namespace skylight
