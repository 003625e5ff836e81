#include "skylight/gpu/sky_render.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <functional>

#include "skylight/core/error.h"
#include "skylight/core/parallel.h"
#include "skylight/models/neural_sky.h"
#include "skylight/models/pietras.h"
#include "skylight/nn/glsl.h"

namespace skylight::gpu {

namespace {

// asin through atan: Mesa's GLSL asin is a polynomial with errors of ~4e-4 rad near 1, its atan
// ~3e-6 rad (measured: ShaderDirectionsMatchTheCpuLayouts, docs/GPU.md).
constexpr const char* kDirectionFromAngles =
    "float skylight_asin(float x) { return atan(x, sqrt(max((1.0 - x) * (1.0 + x), 0.0))); }\n"
    "vec3 skylight_direction(float zenith, float azimuth) {  // core/frame.h\n"
    "  float st = sin(zenith);\n"
    "  return vec3(st * sin(azimuth), st * cos(azimuth), cos(zenith));\n"
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

std::array<float, 3> to_float(Vec3 v) {
  return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
}

}  // namespace

namespace {

// A projection's part of glsl_pixel_direction: what it declares before the function, and the
// function's body up to its last statement (each body ends in `dir = ...;`).
struct PixelDirectionGlsl {
  std::string declarations, body;
};

PixelDirectionGlsl pixel_direction_glsl(const render::RenderSettings& s) {
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

std::string glsl_pixel_direction(const render::RenderSettings& s) {
  const PixelDirectionGlsl parts = pixel_direction_glsl(s);
  std::string g = kDirectionFromAngles;
  g += "uniform vec2 skylight_size;  // width, height [px]\n";
  g += parts.declarations;
  g += "bool skylight_pixel_direction(vec2 pixel, out vec3 dir) {\n";
  g += parts.body;
  g += "  return true;\n}\n";
  return g;
}

namespace {

// The uniforms glsl_pixel_direction declares, for settings s.
void set_layout_uniforms(Program& p, const render::RenderSettings& s) {
  p.set_if_active("skylight_size",
                  std::array<float, 2>{static_cast<float>(s.width), static_cast<float>(s.height)});
  if (s.projection == Projection::fisheye) {
    p.set_if_active("skylight_g_max", static_cast<float>(lens_g_max(s.fisheye)));
    p.set_if_active("skylight_north_angle", static_cast<float>(s.fisheye.north_angle));
  }
  if (s.projection == Projection::camera) {
    const CameraFrame c = camera_frame(s.pinhole);
    p.set_if_active("skylight_forward", to_float(c.f));
    p.set_if_active("skylight_right", to_float(c.right));
    p.set_if_active("skylight_up", to_float(c.up));
    p.set_if_active("skylight_tan_half_fov", static_cast<float>(c.t));
  }
}

// Image pixel (col, row), centres at +0.5 and row 0 at the top, of the fragment.
constexpr const char* kPixel =
    "  vec2 pixel = vec2(gl_FragCoord.x, skylight_size.y - gl_FragCoord.y);\n";

}  // namespace

io::ImageF shader_pixel_directions(const render::RenderSettings& s) {
  validate(s);
  std::string src(kGlslVersion);
  src += glsl_pixel_direction(s);
  src += "out vec4 colour;\nvoid main() {\n";
  src += kPixel;
  src += "  vec3 dir;\n  bool valid = skylight_pixel_direction(pixel, dir);\n";
  src += "  colour = vec4(dir, valid ? 1.0 : 0.0);\n}\n";
  Program p = Program::fullscreen(src);
  set_layout_uniforms(p, s);
  Target t(s.width, s.height);
  t.clear();
  t.draw_fullscreen(p);
  return t.read(4);
}

namespace {

// What the fragment shader needs of a model it can render: the network's GLSL, the uniforms of
// the sky state, the colour of a valid direction `dir`, and the uniforms' values.
struct ShaderSky {
  std::string network, uniforms, rgb;
  std::function<void(Program&)> set;
};

ShaderSky shader_sky(const SkyModel& model) {
  if (const auto* pietras = dynamic_cast<const PietrasSkyModel*>(&model)) {
    // The Pietras network with its shadow test: PietrasSkyModel::rgb of the view, every view
    // (those meeting the ground included).
    const Vec3 sun = model.sun().direction();
    const float altitude = static_cast<float>(pietras->observer_altitude_m());
    return {nn::glsl_pietras_sky(pietras->network()),
            "uniform vec3 skylight_sun;  // unit vector, z up\nuniform float skylight_altitude;\n",
            "skylight_pietras_at(skylight_altitude, dir, skylight_sun)",
            [sun, altitude](Program& p) {
              p.set_if_active("skylight_sun", std::array<float, 3>{static_cast<float>(sun.x),
                                                                   static_cast<float>(sun.y),
                                                                   static_cast<float>(sun.z)});
              p.set_if_active("skylight_altitude", altitude);
            }};
  }
  if (const auto* nn = dynamic_cast<const NeuralSkyModel*>(&model)) {
    const nn::SkyState st = nn->state();
    return {nn::glsl_sky_network(nn->network()),
            "uniform float skylight_sun_zenith, skylight_sun_azimuth, skylight_turbidity;\n"
            "uniform int skylight_sun_up;\n",
            "(skylight_sun_up != 0 ? skylight_sky_state(dir, skylight_sun_zenith, "
            "skylight_sun_azimuth, skylight_turbidity) : vec3(0.0))",
            [st](Program& p) {
              p.set_if_active("skylight_sun_zenith", static_cast<float>(st.sun_zenith));
              p.set_if_active("skylight_sun_azimuth", static_cast<float>(st.sun_azimuth));
              p.set_if_active("skylight_turbidity", static_cast<float>(st.turbidity));
              // NeuralSkyModel returns 0 for a sun below the horizon (models/neural_sky.h).
              p.set_if_active("skylight_sun_up", st.sun_zenith <= kPi / 2 ? 1 : 0);
            }};
  }
  throw InvalidArgument(fmt::format(
      "the GL renderer draws the network models (nn, pietras), not model '{}'", model.name()));
}

}  // namespace

SkyRenderer::SkyRenderer(const SkyModel& model, const render::RenderSettings& s,
                         DirectionSource directions)
    : model_(model), settings_(s) {
  validate(s);
  const ShaderSky sky = shader_sky(model);
  source_ = std::string(kGlslVersion);
  source_ += fmt::format("// skylight: the `{}` sky model by pixel (docs/GPU.md).\n", model.name());
  source_ += sky.network;
  source_ += '\n';
  source_ += glsl_pixel_direction(s);
  source_ += "\n" + sky.uniforms;
  if (directions == DirectionSource::texture)
    source_ += "uniform sampler2D skylight_directions;  // xyz, valid in w\n";
  source_ += "out vec4 colour;\nvoid main() {\n";
  source_ += kPixel;
  if (directions == DirectionSource::texture)
    source_ +=
        "  vec4 d = texelFetch(skylight_directions, ivec2(gl_FragCoord.xy), 0);\n"
        "  vec3 dir = d.xyz;\n"
        "  bool valid = d.w != 0.0;\n";
  else
    source_ += "  vec3 dir;\n  bool valid = skylight_pixel_direction(pixel, dir);\n";
  source_ += "  vec3 rgb = valid ? " + sky.rgb + " : vec3(0.0);\n";
  source_ +=
      "  colour = vec4(rgb, valid ? 1.0 : 0.0);\n"
      "}\n";
  program_ = std::make_unique<Program>(Program::fullscreen(source_));
  Program& p = *program_;
  set_layout_uniforms(p, s);
  sky.set(p);
  if (directions == DirectionSource::texture) {
    const render::PixelDirections d = render::pixel_directions(s);
    io::ImageF img(s.width, s.height, 4);
    for (std::size_t i = 0; i < d.x.size(); ++i) {
      img.data[4 * i] = d.x[i];
      img.data[4 * i + 1] = d.y[i];
      img.data[4 * i + 2] = d.z[i];
      img.data[4 * i + 3] = d.valid[i] ? 1.0f : 0.0f;
    }
    directions_ = std::make_unique<Texture>(img);
    p.bind("skylight_directions", *directions_, 0);
  }
  target_ = std::make_unique<Target>(s.width, s.height);
}

void SkyRenderer::draw() {
  target_->clear();
  target_->draw_fullscreen(*program_);
}

io::ImageF SkyRenderer::read() const {
  return target_->read(4);
}

render::SkyImage SkyRenderer::image() const {
  const render::RenderSettings& s = settings_;
  const io::ImageF rgba = read();
  const std::size_t n = static_cast<std::size_t>(s.width) * static_cast<std::size_t>(s.height);
  render::SkyImage img{io::ImageF(s.width, s.height, 3), io::ImageF(s.width, s.height, 3), {}};
  img.mask.assign(n, 0);
  const bool sky = s.sun != SunMode::sun_only;
  const bool add_sun = s.sun != SunMode::sky && model_.has_sun();
  parallel_for(static_cast<std::size_t>(s.height), 8, [&](std::size_t r0, std::size_t r1) {
    for (std::size_t row = r0; row < r1; ++row) {
      for (int col = 0; col < s.width; ++col) {
        const std::size_t i =
            row * static_cast<std::size_t>(s.width) + static_cast<std::size_t>(col);
        const float* px = rgba.data.data() + 4 * i;
        Rgb rgb{};
        if (px[3] == 0.0f) {
          img.mask[i] = 1;
        } else {
          if (sky) rgb = {px[0], px[1], px[2]};
          if (add_sun) {
            const Xyz sun = render::average_sun_over_pixel(model_, s, col, static_cast<int>(row));
            const Rgb sun_rgb = xyz_to_linear_srgb(sun);
            rgb = {rgb.r + sun_rgb.r, rgb.g + sun_rgb.g, rgb.b + sun_rgb.b};
          }
        }
        img.set(i, linear_srgb_to_xyz(rgb), rgb);
      }
    }
  });
  return img;
}

render::SkyImage render_sky_gpu(const SkyModel& model, const render::RenderSettings& settings) {
  validate(settings);
  Context context;
  SkyRenderer renderer(model, settings);
  renderer.draw();
  return renderer.image();
}

}  // namespace skylight::gpu
