// The per-pixel hot loop of the haze operations (haze/image_haze.h, HazeKernel; Morales et al.
// 2017 eq. 26, docs/HAZE.md "Speed"): Highway SIMD with dynamic dispatch to the best instruction
// set of the running CPU, and the scalar loop it is tested against.
#pragma once

#include <array>
#include <cstddef>

namespace skylight::haze::detail {

// What every pixel reads besides its own value, depth and airlights (a fragment shader's
// uniforms; the Gamma tables as 1D textures).
struct PixelUniforms {
  const float* gs = nullptr;            // Gamma_s table (3 per entry), null: Gamma_s = 1 (add)
  const float* gt = nullptr;            // Gamma_t table, null: Gamma_t = 1 (remove)
  float inv_step = 1.0f;                // 1 / table step [1/m]
  int last = 0;                         // entries - 2
  float min_t = 0.05f;                  // floor of Gamma_s
  std::array<float, 3> a_t{}, scale{};  // I^inf_t and I^inf_t / I^inf_s
};

// Eq. 26 on n pixels in place (RGB interleaved; depth [m], every value in [0, table range]): per
// channel, with the table lookup pos = s inv_step, i = min(floor(pos), last), f = pos - i,
//   r = Gamma_t / max(Gamma_s, min_t),  I_out = max(0, I scale r + a_t (1 - r)),
// a_t and scale taken per pixel from `a_t_map` (RGB; null: the uniforms) and a_t / `a_s_map`
// (null: 1 with a_t_map). Returns the pixels whose Gamma_s fell below min_t in some channel.
std::size_t haze_pixels(const PixelUniforms& u, float* px, const float* depth, const float* a_t_map,
                        const float* a_s_map, std::size_t n);

// The same one pixel at a time: the reference of the SIMD path's test.
std::size_t haze_pixels_scalar(const PixelUniforms& u, float* px, const float* depth,
                               const float* a_t_map, const float* a_s_map, std::size_t n);

}  // namespace skylight::haze::detail
