// The GL paths of the operations (`render --gpu`, `haze add|retarget|remove|composite --gpu`,
// `nn planet`, `bench --models gpu` and `bench --haze`'s frame): the optional gpu/ module is not a
// dependency of the library, so a front end that links it installs its functions here once
// (install_gpu_backend); without them these paths fail saying the build has no GPU module.
#pragma once

#include <functional>

#include "skylight/haze/attenuation.h"
#include "skylight/haze/image_haze.h"
#include "skylight/io/image.h"
#include "skylight/models/pietras.h"
#include "skylight/perf/bench.h"
#include "skylight/render/sky_render.h"

namespace skylight::operations {

struct GpuBackend {
  std::function<render::SkyImage(const SkyModel&, const render::RenderSettings&)> render_sky;
  // haze::apply_haze by a fragment shader (the depth in metres).
  std::function<io::ImageF(const io::ImageF& image, const io::ImageF& depth_m,
                           const haze::CameraSensitivity&, const haze::HazeSettings&,
                           haze::HazeReport*)>
      apply_haze;
  std::function<io::ImageF(const io::ImageF& background, const io::ImageF& object,
                           const io::ImageF& alpha, const io::ImageF& object_depth_m,
                           const haze::CameraSensitivity&, const haze::HazeSettings&)>
      composite;
  std::function<PlanetFrame(const nn::PietrasNetwork&, const PlanetViewOptions&)> planet;
  std::function<void(int repeats, double cpu_wall_s, const perf::Output&)> bench_haze;
  std::function<void(int width, int height, int repeats, const perf::Output&)> bench_frames;
};

void install_gpu_backend(GpuBackend backend);
// The installed backend; `what` (the flag that asked for GL) names the failure without one.
const GpuBackend& gpu_backend(std::string_view what);
bool has_gpu_backend();

}  // namespace skylight::operations
