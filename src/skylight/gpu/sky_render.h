// Every sky model with a GPU form (SkyModel::gpu_sky, models/gpu_sky.h) rendered by a fragment
// shader (docs/GPU.md): per pixel, the direction of render/sky_render.h's layout (ported to GLSL,
// every projection) and the model's function (the networks exported by nn/glsl.h, the Perez and
// Hosek-Wilkie forms with their set-up's uniforms). The result is the same SkyImage as
// render::render_sky; the colour conversion, the mask and the solar disc are done on the CPU after
// the readback.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "skylight/gpu/context.h"
#include "skylight/models/sky_model.h"
#include "skylight/render/glsl_camera.h"
#include "skylight/render/sky_render.h"

namespace skylight::gpu {

// The pixel -> direction GLSL of render/glsl_camera.h (its old home).
using render::glsl_pixel_direction;

// Sets the uniforms of a model's GPU form or a camera (those the compiler kept).
void set_sky_uniforms(Program& p, const std::vector<GpuSky::Uniform>& uniforms);

// The directions the shader computes (glsl_pixel_direction) for every pixel: x, y, z and 1 (a
// direction) or 0 (none) as RGBA, row 0 at the top. Needs a current Context.
io::ImageF shader_pixel_directions(const render::RenderSettings& s);

// Where the fragment shader takes each pixel's direction from.
enum class DirectionSource {
  shader,   // computed in GLSL (glsl_pixel_direction): the render path
  texture,  // render::pixel_directions (double, rounded to float) uploaded as an RGBA32F texture:
            // the network alone against the CPU batch path on identical float inputs
};

// The compiled sky program and its float target for one model and layout.
class SkyRenderer {
 public:
  // Needs a current Context. Throws InvalidArgument for bad settings (validate, core/camera.h) or a
  // model without a GPU form, and GpuError from GL.
  SkyRenderer(const SkyModel& model, const render::RenderSettings& settings,
              DirectionSource directions = DirectionSource::shader);
  // The full fragment shader (for docs and tests).
  const std::string& fragment_source() const { return source_; }
  // Draws one frame into the target (no readback; Context::finish to wait for it).
  void draw();
  // The target read back: the model's native colour (output(): linear sRGB or XYZ) in r, g, b and
  // 1 (a direction) or 0 (none) in alpha.
  io::ImageF read() const;
  GpuSky::Output output() const { return output_; }
  // The frame as render::render_sky returns it (read() + XYZ, mask and solar disc on the CPU).
  render::SkyImage image() const;

 private:
  const SkyModel& model_;
  render::RenderSettings settings_;
  std::string source_;
  GpuSky::Output output_ = GpuSky::Output::rgb;
  std::unique_ptr<Texture> directions_;
  std::vector<std::unique_ptr<Texture>> tables_;
  std::unique_ptr<Program> program_;
  std::unique_ptr<Target> target_;
};

// One frame in a context of its own: render::render_sky(model, settings), computed by GL.
render::SkyImage render_sky_gpu(const SkyModel& model, const render::RenderSettings& settings);

}  // namespace skylight::gpu
