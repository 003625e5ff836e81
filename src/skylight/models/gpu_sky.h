// A sky model as a fragment shader's function (docs/GPU.md, docs/VIEWER.md): the model's own GLSL
// and the values of its uniforms, computed by the model's own set-up on the CPU. Text and numbers
// only (no GL): the `gpu/` renderer, `skylight view`'s WebGL2 page and the tests take the same
// GpuSky. The GLSL is the subset that GLSL 3.30 core and GLSL ES 3.00 both accept (no doubles, no
// implicit int-to-float conversion, no array uniforms), so one source runs on desktop GL and in a
// browser.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace skylight {

struct GpuSky {
  // What `expression` gives: CIE 1931 XYZ (Y in cd/m^2) or linear sRGB (D65), as the model's
  // tristimulus() / rgb() (the one it computes natively).
  enum class Output { xyz, rgb };
  struct Uniform {
    std::string name;
    std::vector<float> values;  // 1..4: float, vec2, vec3, vec4
    bool integer = false;       // an int (values[0])
  };
  // Declarations (uniforms) and functions, no #version line. Every name starts with "skylight_".
  std::string glsl;
  // A GLSL expression of `vec3 dir` (a unit vector, ENU, z up): the sky's colour in that
  // direction, without the solar disc (0 below the horizon, as the model).
  std::string expression;
  Output output = Output::xyz;
  std::vector<Uniform> uniforms;
  // Float tables the function reads with texelFetch (a `uniform sampler2D` of the same name, no
  // filtering): texel (col, row) = data[(row * width + col) * channels + c], row 0 uploaded first
  // (GL's row 0), 3 or 4 channels.
  struct Table {
    std::string name;
    int width = 0, height = 0, channels = 3;
    std::vector<float> data;
  };
  std::vector<Table> tables;
  // The model's set-up in one line, for a page's or a shader's comment.
  std::string comment;
};

// A float/vecN uniform of doubles (rounded to float) and an int uniform.
GpuSky::Uniform gpu_uniform(std::string name, const std::vector<double>& values);
GpuSky::Uniform gpu_int_uniform(std::string name, int value);

// GLSL helpers every model's function may call (declared once per shader by the assembler):
//   float skylight_asin(float x)            asin through atan (Mesa's asin errs ~4e-4 rad near 1)
//   float skylight_angle(vec3 a, vec3 b)    the angle between unit vectors, by the chord
//                                           (2 asin(|a - b| / 2): accurate near 0, core/frame.h)
//   vec3 skylight_srgb_to_xyz(vec3 rgb)     linear sRGB (D65) to XYZ (core/colorimetry.h's matrix)
//   vec3 skylight_xyz_to_srgb(vec3 xyz)
std::string glsl_sky_helpers();

// A full fragment-shader function for `sky`: the helpers, sky.glsl and
//   vec3 skylight_sky_xyz(vec3 dir)  // XYZ, whatever sky.output is
std::string glsl_sky_function(const GpuSky& sky);

}  // namespace skylight
