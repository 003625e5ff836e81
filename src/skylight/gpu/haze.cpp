// Morales et al. 2017 eqs. 10, 19 and 26 in GLSL; docs/HAZE.md, docs/GPU.md.
#include "skylight/gpu/haze.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "skylight/core/error.h"

namespace skylight::gpu {

namespace {

// Table entries per texture row (GL_MAX_TEXTURE_SIZE is at least 1024 in GL 3.3; llvmpipe 16384).
constexpr int kTableRow = 1024;

bool has_source(haze::HazeOperation op) {
  return op != haze::HazeOperation::add;
}
bool has_target(haze::HazeOperation op) {
  return op != haze::HazeOperation::remove;
}

// A Gamma table as an RGB float texture: entry i at (i % kTableRow, i / kTableRow), image rows.
io::ImageF table_image(const haze::AttenuationTable& t) {
  const int n = static_cast<int>(t.size());
  const int width = std::min(n, kTableRow);
  const int rows = (n + kTableRow - 1) / kTableRow;
  io::ImageF img(width, rows, 3);
  std::copy(t.gamma.begin(), t.gamma.end(), img.data.begin());
  return img;
}

// Checks the depth map as haze::depth_in_metres does and returns its largest depth [m] (as the
// CPU path's float map holds it, so that both build their tables on the same grid).
double checked_max_depth(const io::ImageF& depth, const haze::DepthEncoding& e, int width,
                         int height) {
  if (depth.channels != 1 || depth.width != width || depth.height != height)
    throw InvalidArgument(
        fmt::format("the depth map is {}x{} with {} channel(s) but the image is "
                    "{}x{} (one channel expected)",
                    depth.width, depth.height, depth.channels, width, height));
  haze::validate(e);
  const bool normalised = e.near_m.has_value();
  float m = 0.0f;
  for (std::size_t i = 0; i < depth.data.size(); ++i) {
    const float v = depth.data[i];
    if (!std::isfinite(v) || v < 0.0f || (normalised && v > 1.0f))
      throw InvalidArgument(fmt::format("the depth map pixel ({}, {}) is {}; depth must be {}",
                                        i % depth.width, i / depth.width, v,
                                        normalised ? "in [0, 1]" : "finite and >= 0 m"));
    m = std::max(m, v);
  }
  if (!normalised) return m;
  // Eq. 19 increases with s_bar: the largest depth is that of the largest s_bar.
  return static_cast<float>(haze::depth_from_normalised(m, *e.near_m, *e.far_m));
}

// The Gamma tables' uniforms and their linear interpolation (haze::HazeKernel's rule) in GLSL:
// table entry i lies at (i % kTableRow, rows - 1 - i / kTableRow) of its texture.
std::string table_uniforms_source() {
  return "uniform float skylight_inv_step;  // 1 / table step [1/m]\n"
         "uniform int skylight_last;  // entries - 2\n"
         "uniform int skylight_table_rows;\n";
}

std::string table_lerp_source() {
  return fmt::format(
      "vec3 skylight_lerp(sampler2D t, int i, float f) {{\n"
      "  ivec2 a = ivec2(i % {0}, skylight_table_rows - 1 - i / {0});\n"
      "  ivec2 b = ivec2((i + 1) % {0}, skylight_table_rows - 1 - (i + 1) / {0});\n"
      "  vec3 g0 = texelFetch(t, a, 0).rgb;\n"
      "  return g0 + f * (texelFetch(t, b, 0).rgb - g0);\n"
      "}}\n",
      kTableRow);
}

void set_table_uniforms(Program& p, const haze::HazeKernel& k) {
  p.set("skylight_inv_step", static_cast<float>(1.0 / k.step_m));
  p.set("skylight_last", static_cast<int>(k.entries) - 2);
  p.set("skylight_table_rows",
        static_cast<int>((k.entries + kTableRow - 1) / static_cast<std::size_t>(kTableRow)));
}

std::array<float, 3> to_float(const haze::Rgb3& v) {
  return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}

}  // namespace

std::string haze_fragment_source(haze::HazeOperation operation, bool normalised,
                                 bool per_pixel_airlight) {
  const bool source = has_source(operation), target = has_target(operation);
  std::string s(kGlslVersion);
  s += "// skylight: haze by pixel, eq. 26 (Morales et al. 2017; docs/HAZE.md, docs/GPU.md).\n";
  s += "uniform sampler2D skylight_image;  // RGB\n";
  s += "uniform sampler2D skylight_depth;  // r: depth\n";
  if (source) s += "uniform sampler2D skylight_gamma_s;  // Gamma_s table, RGB\n";
  if (target) s += "uniform sampler2D skylight_gamma_t;  // Gamma_t table, RGB\n";
  s += table_uniforms_source();
  s += "uniform float skylight_min_t;  // floor of Gamma_s\n";
  s += "uniform vec3 skylight_airlight_t, skylight_scale;  // I^inf_t, I^inf_t / I^inf_s\n";
  if (normalised) s += "uniform float skylight_near_m, skylight_near_over_far;\n";
  if (per_pixel_airlight) {
    s += "uniform sampler2D skylight_airlight_t_map;  // per-pixel I^inf_t, RGB\n";
    if (source && target) s += "uniform sampler2D skylight_airlight_s_map;  // per-pixel I^inf_s\n";
  }
  s += "out vec4 colour;\n";
  s += table_lerp_source();
  s += "void main() {\n  ivec2 p = ivec2(gl_FragCoord.xy);\n";
  s += "  vec3 v = texelFetch(skylight_image, p, 0).rgb;\n";
  s += "  float s = texelFetch(skylight_depth, p, 0).r;\n";
  // Eq. 19 as s_near / ((1 - s_bar) + s_bar s_near / s_far): 1 - s_bar is exact in float for
  // s_bar >= 1/2, so the far end keeps float precision (1 - s_bar (1 - s_near / s_far) cancels).
  if (normalised) s += "  s = skylight_near_m / ((1.0 - s) + s * skylight_near_over_far);\n";
  s += "  float pos = s * skylight_inv_step;\n"
       "  int i = min(int(pos), skylight_last);\n"
       "  float f = pos - float(i);\n";
  s += target ? "  vec3 ratio = skylight_lerp(skylight_gamma_t, i, f);\n"
              : "  vec3 ratio = vec3(1.0);\n";
  s += "  float below = 0.0;\n";
  if (source)
    s += "  vec3 g_s = skylight_lerp(skylight_gamma_s, i, f);\n"
         "  below = any(lessThan(g_s, vec3(skylight_min_t))) ? 1.0 : 0.0;\n"
         "  ratio /= max(g_s, vec3(skylight_min_t));\n";
  s += "  vec3 a_t = skylight_airlight_t, scale = skylight_scale;\n";
  if (per_pixel_airlight) {
    s += "  a_t = texelFetch(skylight_airlight_t_map, p, 0).rgb;\n";
    s += source && target ? "  scale = a_t / texelFetch(skylight_airlight_s_map, p, 0).rgb;\n"
                          : "  scale = vec3(1.0);\n";
  }
  s += "  vec3 o = v * scale * ratio + a_t * (1.0 - ratio);\n"
       "  colour = vec4(max(o, vec3(0.0)), below);\n"
       "}\n";
  return s;
}

HazeRenderer::HazeRenderer(int width, int height, haze::HazeOperation operation,
                           const haze::DepthEncoding& encoding, bool per_pixel_airlight)
    : width_(width),
      height_(height),
      operation_(operation),
      encoding_(encoding),
      per_pixel_(per_pixel_airlight) {
  program_ = std::make_unique<Program>(Program::fullscreen(
      haze_fragment_source(operation, encoding.near_m.has_value(), per_pixel_airlight)));
  target_ = std::make_unique<Target>(width, height);
}

HazeRenderer::~HazeRenderer() = default;

io::ImageF HazeRenderer::apply(const io::ImageF& image, const io::ImageF& depth,
                               const haze::CameraSensitivity& camera,
                               const haze::HazeSettings& settings, haze::HazeReport* report) {
  if (image.channels != 3)
    throw InvalidArgument(
        fmt::format("the image has {} channel(s); haze needs R, G, B", image.channels));
  SKYLIGHT_CHECK(
      image.width == width_ && image.height == height_ && settings.operation == operation_,
      "HazeRenderer: the frame's size or operation differs from the renderer's");
  SKYLIGHT_CHECK((settings.airlight_source_map != nullptr) == per_pixel_,
                 "HazeRenderer: per-pixel airlight in the settings but not the renderer or back");
  const double far = checked_max_depth(depth, encoding_, width_, height_);
  const haze::HazeKernel k = haze::haze_kernel(far, camera, settings);
  Program& p = *program_;
  const Texture image_tex(image), depth_tex(depth);
  p.bind("skylight_image", image_tex, 0);
  p.bind("skylight_depth", depth_tex, 1);
  std::unique_ptr<Texture> gs, gt;
  if (has_source(operation_)) {
    gs = std::make_unique<Texture>(table_image(k.source));
    p.bind("skylight_gamma_s", *gs, 2);
  }
  if (has_target(operation_)) {
    gt = std::make_unique<Texture>(table_image(k.target));
    p.bind("skylight_gamma_t", *gt, 3);
  }
  set_table_uniforms(p, k);
  p.set_if_active("skylight_min_t", static_cast<float>(k.min_transmission));
  std::unique_ptr<Texture> at_map, as_map;
  if (per_pixel_) {
    for (const auto* map : {k.airlight_target_map.get(), k.airlight_source_map.get()})
      if (map && (map->rgb().width != width_ || map->rgb().height != height_))
        throw InvalidArgument(fmt::format("the per-pixel airlight is {}x{} but the image {}x{}",
                                          map->rgb().width, map->rgb().height, width_, height_));
    at_map = std::make_unique<Texture>(k.airlight_target_map->rgb());
    p.bind("skylight_airlight_t_map", *at_map, 4);
    if (k.airlight_source_map) {
      as_map = std::make_unique<Texture>(k.airlight_source_map->rgb());
      p.bind("skylight_airlight_s_map", *as_map, 5);
    }
  }
  p.set_if_active("skylight_airlight_t", to_float(k.airlight_target));
  p.set_if_active("skylight_scale", to_float(k.scale));
  if (encoding_.near_m) {
    p.set("skylight_near_m", static_cast<float>(*encoding_.near_m));
    p.set("skylight_near_over_far", static_cast<float>(*encoding_.near_m / *encoding_.far_m));
  }
  target_->clear();
  target_->draw_fullscreen(p);
  const io::ImageF rgba = target_->read(4);
  io::ImageF out(width_, height_, 3);
  std::size_t low = 0;
  for (std::size_t i = 0; i < rgba.data.size() / 4; ++i) {
    for (std::size_t c = 0; c < 3; ++c) out.data[3 * i + c] = rgba.data[4 * i + c];
    low += rgba.data[4 * i + 3] != 0.0f ? 1 : 0;
  }
  if (report) {
    report->table_error_bound = k.error_bound();
    report->table_entries = k.entries;
    report->clamped_transmission_pixels = low;
  }
  return out;
}

io::ImageF apply_haze(const io::ImageF& image, const io::ImageF& depth,
                      const haze::DepthEncoding& encoding, const haze::CameraSensitivity& camera,
                      const haze::HazeSettings& settings, haze::HazeReport* report) {
  Context context;
  HazeRenderer renderer(image.width, image.height, settings.operation, encoding,
                        settings.airlight_source_map != nullptr);
  return renderer.apply(image, depth, camera, settings, report);
}

std::string composite_fragment_source(bool per_pixel_airlight) {
  std::string s(kGlslVersion);
  s += "// skylight: composite by pixel, eq. 10 and §6.2 step 3 (Morales et al. 2017; "
       "docs/HAZE.md).\n";
  s += "uniform sampler2D skylight_background;  // RGB, already hazy\n";
  s += "uniform sampler2D skylight_object;  // RGB without haze\n";
  s += "uniform sampler2D skylight_alpha;  // r: coverage in [0, 1]\n";
  s += "uniform sampler2D skylight_depth;  // r: the object's depth [m]\n";
  s += "uniform sampler2D skylight_gamma_t;  // Gamma table, RGB\n";
  s += table_uniforms_source();
  s += "uniform vec3 skylight_airlight_t, skylight_scale;  // I^inf, 1\n";
  if (per_pixel_airlight) s += "uniform sampler2D skylight_airlight_t_map;  // per-pixel I^inf\n";
  s += "out vec4 colour;\n";
  s += table_lerp_source();
  s += "void main() {\n  ivec2 p = ivec2(gl_FragCoord.xy);\n"
       "  vec3 v = texelFetch(skylight_object, p, 0).rgb;\n"
       "  float s = texelFetch(skylight_depth, p, 0).r;\n"
       "  float a = texelFetch(skylight_alpha, p, 0).r;\n"
       "  float pos = s * skylight_inv_step;\n"
       "  int i = min(int(pos), skylight_last);\n"
       "  float f = pos - float(i);\n"
       "  vec3 ratio = skylight_lerp(skylight_gamma_t, i, f);\n";
  s += per_pixel_airlight ? "  vec3 a_t = texelFetch(skylight_airlight_t_map, p, 0).rgb;\n"
                          : "  vec3 a_t = skylight_airlight_t;\n";
  s += "  vec3 hazed = max(v * skylight_scale * ratio + a_t * (1.0 - ratio), vec3(0.0));\n"
       "  vec3 bg = texelFetch(skylight_background, p, 0).rgb;\n"
       "  colour = vec4(a * hazed + (1.0 - a) * bg, 1.0);\n"
       "}\n";
  return s;
}

io::ImageF composite(const io::ImageF& background, const io::ImageF& object,
                     const io::ImageF& alpha, const io::ImageF& object_depth_m,
                     const haze::CameraSensitivity& camera, const haze::HazeSettings& settings) {
  haze::check_composite_inputs(background, object, alpha);
  const int w = background.width, h = background.height;
  const bool per_pixel = settings.airlight_source_map != nullptr;
  haze::HazeSettings add = settings;
  add.operation = haze::HazeOperation::add;
  const double far = checked_max_depth(object_depth_m, {}, w, h);
  const haze::HazeKernel k = haze::haze_kernel(far, camera, add);
  Context context;
  Program p = Program::fullscreen(composite_fragment_source(per_pixel));
  const Texture bg_tex(background), object_tex(object), alpha_tex(alpha), depth_tex(object_depth_m),
      table(table_image(k.target));
  p.bind("skylight_background", bg_tex, 0);
  p.bind("skylight_object", object_tex, 1);
  p.bind("skylight_alpha", alpha_tex, 2);
  p.bind("skylight_depth", depth_tex, 3);
  p.bind("skylight_gamma_t", table, 4);
  set_table_uniforms(p, k);
  p.set_if_active("skylight_airlight_t", to_float(k.airlight_target));
  p.set("skylight_scale", to_float(k.scale));
  std::unique_ptr<Texture> map;
  if (per_pixel) {
    const io::ImageF& rgb = k.airlight_target_map->rgb();
    if (rgb.width != w || rgb.height != h)
      throw InvalidArgument(fmt::format("the per-pixel airlight is {}x{} but the image {}x{}",
                                        rgb.width, rgb.height, w, h));
    map = std::make_unique<Texture>(rgb);
    p.bind("skylight_airlight_t_map", *map, 5);
  }
  Target target(w, h);
  target.clear();
  target.draw_fullscreen(p);
  return target.read(3);
}

}  // namespace skylight::gpu
