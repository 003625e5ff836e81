// A camera's pixel -> direction mapping (core/camera.h, Camera::direction) as GLSL: the one source
// of the GL renderer (gpu/sky_render.h) and of `skylight view`'s WebGL2 page (docs/VIEWER.md).
// Text and numbers only, no GL; the subset GLSL 3.30 core and GLSL ES 3.00 share.
#pragma once

#include <string>
#include <vector>

#include "skylight/core/camera.h"
#include "skylight/models/gpu_sky.h"

namespace skylight::render {

// GLSL of Camera::direction for s.projection (no #version line; it calls skylight_asin of
// glsl_sky_helpers(), models/gpu_sky.h, which the shader declares before it):
//   bool skylight_pixel_direction(vec2 pixel, out vec3 dir)
// pixel = (col, row) continuous with centres at +0.5, row 0 at the top; false (dir = zenith)
// where the layout has no direction. A calibrated fisheye throws InvalidArgument (the GPU draws
// the centred image circle; a photo's calibrated camera is read on the CPU only).
std::string glsl_pixel_direction(const Camera& s);

// The values of the uniforms glsl_pixel_direction declares (the size; the fisheye's g(fov / 2)
// and north angle; the pinhole camera's frame, computed in double).
std::vector<GpuSky::Uniform> glsl_camera_uniforms(const Camera& s);

}  // namespace skylight::render
