// Facts about the machine the library runs on.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

namespace skylight {

// Memory the system can still give this process without swapping [bytes] (Linux: MemAvailable of
// /proc/meminfo), or nullopt where it cannot be read.
std::optional<std::size_t> available_memory_bytes();

// Throws IoError "<what> needs about X GiB of memory; Y GiB is available" when `bytes` exceeds the
// available memory (nothing is checked where it is unknown).
void require_memory(std::size_t bytes, std::string_view what);

// CPU time [s] used so far by the calling thread, and by all threads of the process: the clocks of
// limits that must not depend on the machine's load (training budgets) and of benchmarks.
double thread_cpu_s();
double process_cpu_s();

}  // namespace skylight
