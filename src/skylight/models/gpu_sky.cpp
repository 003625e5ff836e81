#include "skylight/models/gpu_sky.h"

#include <fmt/format.h>

#include <string>
#include <type_traits>
#include <utility>

#include "skylight/core/colorimetry.h"

namespace skylight {

namespace {

// A GLSL float literal that round-trips the float nearest v.
std::string literal(double v) {
  return fmt::format("{:.9e}", static_cast<float>(v));
}

// mat3(...) takes columns: column j is the matrix applied to the j-th unit vector.
template <class From, class To>
std::string glsl_matrix(To (*convert)(const From&)) {
  std::string s = "mat3(";
  for (int j = 0; j < 3; ++j) {
    From e{};
    double* unit[3];
    if constexpr (std::is_same_v<From, Rgb>) {
      unit[0] = &e.r, unit[1] = &e.g, unit[2] = &e.b;
    } else {
      unit[0] = &e.X, unit[1] = &e.Y, unit[2] = &e.Z;
    }
    *unit[j] = 1.0;
    const To c = convert(e);
    if constexpr (std::is_same_v<To, Rgb>) {
      s += fmt::format("{}{}, {}, {}", j ? ", " : "", literal(c.r), literal(c.g), literal(c.b));
    } else {
      s += fmt::format("{}{}, {}, {}", j ? ", " : "", literal(c.X), literal(c.Y), literal(c.Z));
    }
  }
  return s + ")";
}

}  // namespace

GpuSky::Uniform gpu_uniform(std::string name, const std::vector<double>& values) {
  GpuSky::Uniform u{std::move(name), {}, false};
  for (const double v : values) u.values.push_back(static_cast<float>(v));
  return u;
}

GpuSky::Uniform gpu_int_uniform(std::string name, int value) {
  return {std::move(name), {static_cast<float>(value)}, true};
}

std::string glsl_sky_helpers() {
  std::string s =
      "float skylight_asin(float x) { return atan(x, sqrt(max((1.0 - x) * (1.0 + x), 0.0))); }\n"
      "float skylight_angle(vec3 a, vec3 b) {\n"
      "  return 2.0 * skylight_asin(min(0.5 * length(a - b), 1.0));\n"
      "}\n";
  s += "vec3 skylight_srgb_to_xyz(vec3 rgb) { return " +
       glsl_matrix<Rgb, Xyz>(&linear_srgb_to_xyz) + " * rgb; }\n";
  s += "vec3 skylight_xyz_to_srgb(vec3 xyz) { return " +
       glsl_matrix<Xyz, Rgb>(&xyz_to_linear_srgb) + " * xyz; }\n";
  return s;
}

std::string glsl_sky_function(const GpuSky& sky) {
  std::string s = glsl_sky_helpers();
  if (!sky.comment.empty()) s += "// " + sky.comment + "\n";
  s += sky.glsl;
  s += "vec3 skylight_sky_xyz(vec3 dir) {\n";
  if (sky.output == GpuSky::Output::xyz) {
    s += "  return " + sky.expression + ";\n";
  } else {
    s += "  return skylight_srgb_to_xyz(" + sky.expression + ");\n";
  }
  s += "}\n";
  return s;
}

}  // namespace skylight
