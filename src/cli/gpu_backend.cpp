#include "gpu_backend.h"

#include "skylight/operations/gpu_backend.h"
#ifdef SKYLIGHT_HAVE_GPU
#include "skylight/gpu/bench.h"
#include "skylight/gpu/haze.h"
#include "skylight/gpu/planet.h"
#include "skylight/gpu/sky_render.h"
#endif

namespace skylight::frontend {

void install_gpu_backend() {
#ifdef SKYLIGHT_HAVE_GPU
  operations::install_gpu_backend(
      {.render_sky = gpu::render_sky_gpu,
       .apply_haze =
           [](const io::ImageF& image, const io::ImageF& depth_m,
              const haze::CameraSensitivity& camera, const haze::HazeSettings& settings,
              haze::HazeReport* report) {
             return gpu::apply_haze(image, depth_m, {}, camera, settings, report);
           },
       .composite = gpu::composite,
       .planet = gpu::render_planet_view,
       .bench_haze = gpu::bench_haze,
       .bench_frames = gpu::bench_frames});
#endif
}

}  // namespace skylight::frontend
