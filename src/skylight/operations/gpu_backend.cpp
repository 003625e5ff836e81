#include "skylight/operations/gpu_backend.h"

#include <fmt/format.h>

#include <mutex>
#include <optional>
#include <stdexcept>

namespace skylight::operations {
namespace {

std::mutex g_mutex;
std::optional<GpuBackend> g_backend;

}  // namespace

void install_gpu_backend(GpuBackend backend) {
  const std::lock_guard lock(g_mutex);
  g_backend = std::move(backend);
}

bool has_gpu_backend() {
  const std::lock_guard lock(g_mutex);
  return g_backend.has_value();
}

const GpuBackend& gpu_backend(std::string_view what) {
  const std::lock_guard lock(g_mutex);
  if (!g_backend)
    throw std::runtime_error(fmt::format(
        "{}: this skylight was built without the GPU module (SKYLIGHT_GPU=OFF: EGL and OpenGL "
        "were not found when configuring; docs/GPU.md)",
        what));
  return *g_backend;
}

}  // namespace skylight::operations
