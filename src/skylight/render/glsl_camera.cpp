#include "skylight/render/glsl_camera.h"

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "skylight/core/error.h"
#include "skylight/core/math.h"

namespace skylight::render {

namespace {

// skylight_asin is glsl_sky_helpers()'s (asin through atan: Mesa's GLSL asin is a polynomial with
// errors of ~4e-4 rad near 1, its atan ~3e-6 rad; measured: ShaderDirectionsMatchTheCpuLayouts,
// docs/GPU.md).
// cos(zenith) as 1 - 2 sin^2(zenith / 2): a GPU's cos may err by ~1e-4 absolute near 0
// (SwiftShader, measured: 0.13 deg of zenith angle at 1.6 deg from the zenith), while the half
// angle's sine keeps its relative accuracy; z is then exact to a few ulp at every zenith angle.
constexpr const char* kDirectionFromAngles =
    "vec3 skylight_direction(float zenith, float azimuth) {  // core/frame.h\n"
    "  float st = sin(zenith);\n"
    "  float h = sin(0.5 * zenith);\n"
    "  return vec3(st * sin(azimuth), st * cos(azimuth), 1.0 - 2.0 * h * h);\n"
    "}\n";

std::string pi_literal() {
  return fmt::format("{:.8e}", static_cast<float>(kPi));
}

// The lens mapping g(theta) of core/frame.h at the field-of-view edge.
double lens_g_max(const FisheyeLayout& f) {
  return fisheye_lens_mapping(f.lens, 0.5 * f.fov).value_or(0.5 * f.fov);
}

std::string fisheye_theta_glsl(FisheyeLens lens) {
  switch (lens) {
    case FisheyeLens::equidistant:
      return "g";
    case FisheyeLens::equisolid:
      return "2.0 * skylight_asin(min(0.5 * g, 1.0))";
    case FisheyeLens::orthographic:
      return "skylight_asin(min(g, 1.0))";
    case FisheyeLens::stereographic:
      return "2.0 * atan(0.5 * g)";
  }
  return "g";
}

// Pinhole camera frame of render/sky_render.cpp (camera_direction), in double.
struct CameraFrame {
  Vec3 f, right, up;
  double t;
};
CameraFrame camera_frame(const PinholeLayout& c) {
  const Vec3 f = direction_from_angles(c.look_zenith, c.look_azimuth);
  Vec3 right = cross(f, Vec3{0, 0, 1});
  if (dot(right, right) < 1e-12) right = cross(f, Vec3{0, 1, 0});
  right = normalize(right);
  return {f, right, cross(right, f), std::tan(0.5 * c.vertical_fov)};
}

}  // namespace

namespace {

// A projection's part of glsl_pixel_direction: what it declares before the function, and the
// function's body up to its last statement (each body ends in `dir = ...;`).
struct PixelDirectionGlsl {
  std::string declarations, body;
};

PixelDirectionGlsl pixel_direction_glsl(const Camera& s) {
  PixelDirectionGlsl g;
  switch (s.projection) {
    case Projection::equirect:
    case Projection::hemisphere:
      // theta = pi (row + 0.5) / height (hemisphere: pi/2 ...), phi = 2 pi (col + 0.5) / width.
      g.body += fmt::format("  float theta = {} * {} * pixel.y / skylight_size.y;\n",
                            s.projection == Projection::hemisphere ? "0.5" : "1.0", pi_literal());
      g.body += fmt::format("  float phi = 2.0 * {} * pixel.x / skylight_size.x;\n", pi_literal());
      g.body += "  dir = skylight_direction(theta, phi);\n";
      break;
    case Projection::fisheye:
      // The GL port draws the centred image circle of render; a calibrated layout (a photo's
      // camera, io/camera_calibration.h) is read on the CPU only.
      if (s.fisheye.calibrated())
        throw InvalidArgument("the GPU renders the centred fisheye layout, not a calibrated one");
      g.declarations += "uniform float skylight_g_max;        // lens g(fov / 2)\n";
      g.declarations += "uniform float skylight_north_angle;  // [rad]\n";
      g.body += "  float radius_px = 0.5 * min(skylight_size.x, skylight_size.y);\n";
      g.body += "  float dx = (pixel.x - 0.5 * skylight_size.x) / radius_px;\n";
      g.body += "  float dy = (pixel.y - 0.5 * skylight_size.y) / radius_px;\n";
      g.body += "  float r = length(vec2(dx, dy));\n";
      g.body += "  dir = vec3(0.0, 0.0, 1.0);\n  if (r > 1.0) return false;\n";
      g.body += "  float g = r * skylight_g_max;\n";
      g.body += fmt::format("  float theta = {};\n", fisheye_theta_glsl(s.fisheye.lens));
      g.body += "  float phi = r > 0.0 ? atan(-dx, -dy) - skylight_north_angle : 0.0;\n";
      g.body += "  dir = skylight_direction(theta, phi);\n";
      break;
    case Projection::cubemap:
      g.declarations +=
          "const vec3 kFaceForward[6] = vec3[6](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0),\n"
          "    vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1));\n"
          "const vec3 kFaceRight[6] = vec3[6](vec3(0, -1, 0), vec3(0, 1, 0), vec3(1, 0, 0),\n"
          "    vec3(-1, 0, 0), vec3(-1, 0, 0), vec3(1, 0, 0));\n"
          "const vec3 kFaceUp[6] = vec3[6](vec3(0, 0, 1), vec3(0, 0, 1), vec3(0, 0, 1),\n"
          "    vec3(0, 0, 1), vec3(0, 1, 0), vec3(0, 1, 0));\n";
      g.body += "  float size = skylight_size.y;\n";
      g.body += "  int face = clamp(int(pixel.x / size), 0, 5);\n";
      g.body += "  float a = 2.0 * (pixel.x - float(face) * size) / size - 1.0;\n";
      g.body += "  float b = 1.0 - 2.0 * pixel.y / size;\n";
      g.body +=
          "  dir = normalize(kFaceForward[face] + a * kFaceRight[face] + b * kFaceUp[face]);\n";
      break;
    case Projection::camera:
      g.declarations += "uniform vec3 skylight_forward, skylight_right, skylight_up;\n";
      g.declarations += "uniform float skylight_tan_half_fov;\n";
      g.body +=
          "  float x = (2.0 * pixel.x / skylight_size.y - skylight_size.x / skylight_size.y) *\n"
          "            skylight_tan_half_fov;\n";
      g.body += "  float y = (1.0 - 2.0 * pixel.y / skylight_size.y) * skylight_tan_half_fov;\n";
      g.body += "  dir = normalize(skylight_forward + x * skylight_right + y * skylight_up);\n";
      break;
  }
  return g;
}

}  // namespace

std::string glsl_pixel_direction(const Camera& s) {
  const PixelDirectionGlsl parts = pixel_direction_glsl(s);
  std::string g = kDirectionFromAngles;
  g += "uniform vec2 skylight_size;  // width, height [px]\n";
  g += parts.declarations;
  g += "bool skylight_pixel_direction(vec2 pixel, out vec3 dir) {\n";
  g += parts.body;
  g += "  return true;\n}\n";
  return g;
}

std::vector<GpuSky::Uniform> glsl_camera_uniforms(const Camera& s) {
  std::vector<GpuSky::Uniform> u{
      gpu_uniform("skylight_size", {static_cast<double>(s.width), static_cast<double>(s.height)})};
  if (s.projection == Projection::fisheye) {
    u.push_back(gpu_uniform("skylight_g_max", {lens_g_max(s.fisheye)}));
    u.push_back(gpu_uniform("skylight_north_angle", {s.fisheye.north_angle}));
  }
  if (s.projection == Projection::camera) {
    const CameraFrame c = camera_frame(s.pinhole);
    u.push_back(gpu_uniform("skylight_forward", {c.f.x, c.f.y, c.f.z}));
    u.push_back(gpu_uniform("skylight_right", {c.right.x, c.right.y, c.right.z}));
    u.push_back(gpu_uniform("skylight_up", {c.up.x, c.up.y, c.up.z}));
    u.push_back(gpu_uniform("skylight_tan_half_fov", {c.t}));
  }
  return u;
}

}  // namespace skylight::render
