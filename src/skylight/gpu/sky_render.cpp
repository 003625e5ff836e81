#include "skylight/gpu/sky_render.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

#include "skylight/core/error.h"
#include "skylight/core/parallel.h"
#include "skylight/models/gpu_sky.h"
#include "skylight/render/glsl_camera.h"

namespace skylight::gpu {

namespace {

// Image pixel (col, row), centres at +0.5 and row 0 at the top, of the fragment.
constexpr const char* kPixel =
    "  vec2 pixel = vec2(gl_FragCoord.x, skylight_size.y - gl_FragCoord.y);\n";

}  // namespace

io::ImageF shader_pixel_directions(const render::RenderSettings& s) {
  validate(s);
  std::string src(kGlslVersion);
  src += glsl_sky_helpers();
  src += glsl_pixel_direction(s);
  src += "out vec4 colour;\nvoid main() {\n";
  src += kPixel;
  src += "  vec3 dir;\n  bool valid = skylight_pixel_direction(pixel, dir);\n";
  src += "  colour = vec4(dir, valid ? 1.0 : 0.0);\n}\n";
  Program p = Program::fullscreen(src);
  set_sky_uniforms(p, render::glsl_camera_uniforms(s));
  Target t(s.width, s.height);
  t.clear();
  t.draw_fullscreen(p);
  return t.read(4);
}

namespace {

// The model's shader function (SkyModel::gpu_sky), or InvalidArgument naming the model.
GpuSky shader_sky(const SkyModel& model) {
  std::optional<GpuSky> sky = model.gpu_sky();
  if (!sky) {
    const ModelInfo* info = find_model(model.name());
    throw InvalidArgument(fmt::format("model '{}' has no GPU form{}", model.name(),
                                      info && !info->no_gpu.empty() ? ": " + info->no_gpu : ""));
  }
  return *sky;
}

}  // namespace

void set_sky_uniforms(Program& p, const std::vector<GpuSky::Uniform>& uniforms) {
  for (const GpuSky::Uniform& u : uniforms) {
    UniformValue v;
    if (u.integer) {
      v = static_cast<int>(u.values.at(0));
    } else if (u.values.size() == 1) {
      v = u.values[0];
    } else if (u.values.size() == 2) {
      v = std::array<float, 2>{u.values[0], u.values[1]};
    } else if (u.values.size() == 3) {
      v = std::array<float, 3>{u.values[0], u.values[1], u.values[2]};
    } else {
      v = std::array<float, 4>{u.values.at(0), u.values.at(1), u.values.at(2), u.values.at(3)};
    }
    p.set_if_active(u.name, v);
  }
}

SkyRenderer::SkyRenderer(const SkyModel& model, const render::RenderSettings& s,
                         DirectionSource directions)
    : model_(model), settings_(s) {
  validate(s);
  const GpuSky sky = shader_sky(model);
  output_ = sky.output;
  source_ = std::string(kGlslVersion);
  source_ += fmt::format("// skylight: the `{}` sky model by pixel (docs/GPU.md).\n", model.name());
  source_ += glsl_sky_function(sky);
  source_ += '\n';
  source_ += glsl_pixel_direction(s);
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
  // The model's native colour (GpuSky::output), converted on the CPU after the readback.
  source_ += "  vec3 c = valid ? " + sky.expression + " : vec3(0.0);\n";
  source_ +=
      "  colour = vec4(c, valid ? 1.0 : 0.0);\n"
      "}\n";
  program_ = std::make_unique<Program>(Program::fullscreen(source_));
  Program& p = *program_;
  set_sky_uniforms(p, render::glsl_camera_uniforms(s));
  set_sky_uniforms(p, sky.uniforms);
  // The model's tables on the units after the directions' (GpuSky::Table: row 0 uploaded first;
  // Texture flips an image's rows, so the image holds them bottom-up).
  for (const GpuSky::Table& t : sky.tables) {
    io::ImageF img(t.width, t.height, t.channels);
    const std::size_t row = static_cast<std::size_t>(t.width) * t.channels;
    for (int r = 0; r < t.height; ++r)
      std::copy_n(t.data.begin() + static_cast<std::ptrdiff_t>(r * row), row,
                  img.data.begin() + static_cast<std::ptrdiff_t>((t.height - 1 - r) * row));
    tables_.push_back(std::make_unique<Texture>(img));
    p.bind(t.name, *tables_.back(), static_cast<int>(tables_.size()));
  }
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
          if (sky) {
            rgb = output_ == GpuSky::Output::rgb ? Rgb{px[0], px[1], px[2]}
                                                 : xyz_to_linear_srgb(Xyz{px[0], px[1], px[2]});
          }
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
