// The haze kernel of haze/image_haze.h (Morales et al. 2017 eqs. 10, 19 and 26; docs/HAZE.md)
// as a fragment shader (docs/GPU.md): image and depth as float textures, the Gamma_s and Gamma_t
// tables (haze::HazeKernel) as float textures read with the CPU kernel's own linear
// interpolation, airlights and the transmission floor as uniforms, or per-pixel airlights
// (haze::AirlightMap, Morales 2017 §6.2 step 3) as RGB textures. Add, remove and retarget.
#pragma once

#include <memory>
#include <string>

#include "skylight/gpu/context.h"
#include "skylight/haze/image_haze.h"

namespace skylight::gpu {

// The fragment shader of an operation (for docs and tests). `normalised`: the depth texture holds
// eq. 19's s_bar in [0, 1] and the shader converts it with the uniforms skylight_near_m and
// skylight_far_m; otherwise metres. `per_pixel_airlight`: the airlights are RGB textures of the
// image's size (haze::HazeSettings::airlight_source_map, airlight_target_map).
std::string haze_fragment_source(haze::HazeOperation operation, bool normalised,
                                 bool per_pixel_airlight = false);

// The compiled program and its target for one image size, operation and depth encoding; frames
// are uploaded, drawn and read back one at a time (the per-frame path of `skylight bench --haze`).
class HazeRenderer {
 public:
  // Needs a current Context. Throws GpuError from GL.
  HazeRenderer(int width, int height, haze::HazeOperation operation,
               const haze::DepthEncoding& encoding, bool per_pixel_airlight = false);
  ~HazeRenderer();
  HazeRenderer(const HazeRenderer&) = delete;
  HazeRenderer& operator=(const HazeRenderer&) = delete;

  // One frame: `image` (RGB) and `depth` (one channel, encoded as given to the constructor; both
  // of the renderer's size, values checked as haze::depth_in_metres does) uploaded with the
  // kernel's tables, drawn and read back as RGB. `report` as haze::apply_haze fills it.
  io::ImageF apply(const io::ImageF& image, const io::ImageF& depth,
                   const haze::CameraSensitivity& camera, const haze::HazeSettings& settings,
                   haze::HazeReport* report = nullptr);

 private:
  int width_, height_;
  haze::HazeOperation operation_;
  haze::DepthEncoding encoding_;
  bool per_pixel_;
  std::unique_ptr<Program> program_;
  std::unique_ptr<Target> target_;
};

// One operation in a context of its own: haze::apply_haze(image, depth_in_metres(depth), camera,
// settings) computed by GL. `depth` is in metres, or normalised (eq. 19) when `encoding` has near
// and far.
io::ImageF apply_haze(const io::ImageF& image, const io::ImageF& depth,
                      const haze::DepthEncoding& encoding, const haze::CameraSensitivity& camera,
                      const haze::HazeSettings& settings, haze::HazeReport* report = nullptr);

// The composite of haze::composite (Morales et al. 2017 eq. 10, §6.2 step 3) as a fragment shader:
// the object's RGB hazed at the settings' turbidity (eq. 10 through the Gamma table of
// haze::HazeKernel, add) and laid over the background, alpha I_VO,hazed + (1 - alpha) I_BG, in
// the CPU path's float arithmetic. With `per_pixel_airlight` I^inf is read per pixel from a
// texture (the AirlightMap of an image camera, §6.2 step 2, haze/airlight_field.h).
std::string composite_fragment_source(bool per_pixel_airlight = false);

// haze::composite computed by GL in a context of its own: the same inputs (object depth in
// metres), checks and errors, a constant or a per-pixel airlight (settings' airlight_source_map,
// of the image's size: InvalidArgument otherwise).
io::ImageF composite(const io::ImageF& background, const io::ImageF& object,
                     const io::ImageF& alpha, const io::ImageF& object_depth_m,
                     const haze::CameraSensitivity& camera, const haze::HazeSettings& settings);

}  // namespace skylight::gpu
