// `skylight render`: a sky model into an image (EXR, HDR, PFM or a PNG preview by extension), with
// optional tone-mapped preview and log-luminance false-colour map. `--gpu` renders the `nn` model
// with the headless GL module instead (gpu/sky_render.h, docs/GPU.md).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common.h"
#include "skylight/core/error.h"
#include "skylight/io/image.h"
#include "skylight/render/false_colour.h"
#include "skylight/render/sky_render.h"
#include "skylight/render/tonemap.h"
#ifdef SKYLIGHT_HAVE_GPU
#include "skylight/gpu/sky_render.h"
#endif

namespace skylight::cli {
namespace {

struct RenderFlags {
  ModelOptions model;
  std::string projection = "equirect";
  FisheyeFlags fisheye;  // --lens, --fov (fisheye default 180, camera default 60), --north-angle
  double look_elevation_deg = 0.0, look_azimuth_deg = 0.0;
  int width = 1024, height = 512;
  bool width_given = false;  // cubemap: without --width the width is 6 x height
  std::string output, preview, false_colour;
  std::vector<double> fc_range{0.0, 6.0};
  bool gpu = false;
};

// `--gpu`: the fragment-shader render of a network model (gpu/sky_render.h).
render::SkyImage render_on_gpu(const SkyModel& model, const render::RenderSettings& s) {
#ifdef SKYLIGHT_HAVE_GPU
  return gpu::render_sky_gpu(model, s);
#else
  (void)model, (void)s;
  throw std::runtime_error(
      "--gpu: this skylight was built without the GPU module (SKYLIGHT_GPU=OFF: EGL and OpenGL "
      "were not found when configuring; docs/GPU.md)");
#endif
}

// Default vertical field of view of the camera projection [deg] (fisheye: kFisheyeFovDeg).
constexpr double kCameraFovDeg = 60.0;

// Flags that only some projections read: given with another projection they are ignored with a
// warning.
void warn_unused_projection_flags(const CLI::App& cmd, Projection projection,
                                  std::string_view projection_name) {
  const bool fisheye = projection == Projection::fisheye;
  const bool camera = projection == Projection::camera;
  const std::pair<const char*, bool> flags[] = {{"--lens", fisheye},
                                                {"--north-angle", fisheye},
                                                {"--fov", fisheye || camera},
                                                {"--look-elevation", camera},
                                                {"--look-azimuth", camera}};
  std::string unused;
  for (const auto& [name, used] : flags)
    if (!used && cmd.count(name) > 0) unused += (unused.empty() ? "" : ", ") + std::string(name);
  if (!unused.empty())
    warn(fmt::format("{} not used by --projection {}; ignored", unused, projection_name));
}

// A copy of `md` whose skylight:pixel_unit is `unit`.
io::Metadata with_pixel_unit(io::Metadata md, std::string unit) {
  for (auto& [key, value] : md)
    if (key == "skylight:pixel_unit") value = unit;
  return md;
}

// What the pixels of each output are (skylight:pixel_unit).
constexpr const char* kFloatPixelUnit = "linear sRGB (D65), Y = luminance [cd/m^2]";
constexpr const char* kPreviewPixelUnit =
    "tone-mapped display values (8-bit sRGB: 99th percentile of luminance -> 1, Reinhard, sRGB "
    "curve), not luminance";

int run_render(const RenderFlags& f, const CLI::App& cmd) {
  render::RenderSettings s;
  s.projection = *parse_projection(f.projection);
  s.height = f.height;
  s.width = s.projection == Projection::cubemap && !f.width_given ? 6 * f.height : f.width;
  s.fisheye = f.fisheye.layout(kFisheyeFovDeg);
  s.pinhole.look_zenith = deg_to_rad(90.0 - f.look_elevation_deg);
  s.pinhole.look_azimuth = wrap_azimuth(deg_to_rad(f.look_azimuth_deg));
  s.pinhole.vertical_fov = deg_to_rad(f.fisheye.fov_deg.value_or(kCameraFovDeg));
  s.sun = f.model.sun_only()      ? render::SunMode::sun_only
          : f.model.include_sun() ? render::SunMode::sky_and_sun
                                  : render::SunMode::sky;
  warn_unused_projection_flags(cmd, s.projection, f.projection);
  validate(s);
  (void)io::format_from_path(f.output);
  if (!f.preview.empty() && io::format_from_path(f.preview) != io::ImageFormat::png)
    throw InvalidArgument(fmt::format("--preview '{}' must be a .png file", f.preview));
  if (!f.false_colour.empty() && io::format_from_path(f.false_colour) != io::ImageFormat::png)
    throw InvalidArgument(fmt::format("--false-colour '{}' must be a .png file", f.false_colour));
  if (!(f.fc_range[0] < f.fc_range[1]))
    throw InvalidArgument(fmt::format("--false-colour-range {},{}: LO must be below HI",
                                      f.fc_range[0], f.fc_range[1]));
  const auto model = f.model.make();
  warn_domain(*model);
  const render::SkyImage img = f.gpu ? render_on_gpu(*model, s) : render::render_sky(*model, s);
  // No output may hold NaN or Inf: a model that overflows is an error, and nothing is written.
  const auto bad = std::count_if(img.rgb.data.begin(), img.rgb.data.end(),
                                 [](float v) { return !std::isfinite(v); });
  if (bad > 0)
    throw InvalidArgument(fmt::format(
        "model '{}' gives {} non-finite pixel values (overflow) with these parameters; nothing "
        "was written",
        model->name(), bad));

  auto md = model_metadata(*model, s.sun == render::SunMode::sun_only      ? "sun-only"
                                   : s.sun == render::SunMode::sky_and_sun ? "sky+sun"
                                                                           : "sky");
  for (auto& entry : f.model.solar_position_metadata()) md.push_back(std::move(entry));
  md.emplace_back("skylight:projection", f.projection);
  if (f.gpu) md.emplace_back("skylight:renderer", "gpu (OpenGL fragment shader, docs/GPU.md)");
  if (s.projection == Projection::camera) {
    md.emplace_back("skylight:fov_deg",
                    fmt::format("{}", f.fisheye.fov_deg.value_or(kCameraFovDeg)));
    md.emplace_back("skylight:look_elevation_deg", fmt::format("{}", f.look_elevation_deg));
    md.emplace_back("skylight:look_azimuth_deg", fmt::format("{}", f.look_azimuth_deg));
  }
  if (s.projection == Projection::fisheye) {
    md.emplace_back("skylight:lens", f.fisheye.lens);
    md.emplace_back("skylight:fov_deg",
                    fmt::format("{}", f.fisheye.fov_deg.value_or(kFisheyeFovDeg)));
    md.emplace_back("skylight:north_angle_deg", fmt::format("{}", f.fisheye.north_angle_deg));
  }
  md.emplace_back("skylight:pixel_unit", kFloatPixelUnit);
  // What the model actually used: its zenith luminance and where it stands in its domain.
  md.emplace_back("skylight:zenith_luminance_evaluated_cd_m2",
                  fmt::format("{}", model->tristimulus({0.0, 0.0, 1.0}).Y));
  md.emplace_back("skylight:domain", std::string(to_string(model->domain().worst())));
  const bool output_is_png = io::format_from_path(f.output) == io::ImageFormat::png;
  render::write_image_or_preview(f.output, img.rgb,
                                 output_is_png ? with_pixel_unit(md, kPreviewPixelUnit) : md);
  if (!f.preview.empty())
    render::write_image_or_preview(f.preview, img.rgb, with_pixel_unit(md, kPreviewPixelUnit));
  if (!f.false_colour.empty()) {
    io::ImageF lum(img.xyz.width, img.xyz.height, 1);
    for (std::size_t i = 0; i < lum.data.size(); ++i) lum.data[i] = img.xyz.data[3 * i + 1];
    render::FalseColourOptions fo;
    fo.log10_min = f.fc_range[0];
    fo.log10_max = f.fc_range[1];
    io::write_png(f.false_colour, render::false_colour(lum, fo, &img.mask),
                  with_pixel_unit(md, fmt::format("false colour of log10 luminance, {} to {} "
                                                  "log10 cd/m^2 (legend in the image)",
                                                  fo.log10_min, fo.log10_max)));
  }
  return kExitOk;
}

}  // namespace

void add_render_command(CLI::App& app, Commands& commands) {
  auto f = std::make_shared<RenderFlags>();
  auto* cmd = app.add_subcommand("render",
                                 "render a sky into an image (EXR, HDR, PFM or PNG by extension)");
  f->model.add(*cmd);
  cmd->add_option("--projection", f->projection,
                  "equirect|hemisphere|fisheye|cubemap|camera (perspective, e.g. of the planet "
                  "from orbit with --observer-altitude); default equirect")
      ->check(CLI::IsMember({"equirect", "hemisphere", "fisheye", "cubemap", "camera"}));
  f->fisheye.add(*cmd, "180 (fisheye), 60 (camera)",
                 "fisheye: field of view across the image circle: (0, 360], orthographic (0, 180], "
                 "stereographic (0, 360); camera: vertical field of view, (0, 180)");
  add_number(*cmd,
             {"look-elevation", "deg", ParameterKind::number, -90.0, 90.0, 1, ParameterValue(0.0),
              "camera: elevation of the view centre"},
             f->look_elevation_deg);
  add_number(*cmd,
             {"look-azimuth", "deg", ParameterKind::number, -360.0, 360.0, 1, ParameterValue(0.0),
              "camera: azimuth of the view centre from north towards east"},
             f->look_azimuth_deg);
  add_integer(*cmd,
              {"width", "px", ParameterKind::integer, 1, kMaxImageSide, 1,
               ParameterValue(static_cast<double>(f->width)),
               "image width (cubemap: must be 6 x height, which is its default)"},
              f->width)
      ->each([f](const std::string&) { f->width_given = true; });
  add_integer(*cmd,
              {"height", "px", ParameterKind::integer, 1, kMaxImageSide, 1,
               ParameterValue(static_cast<double>(f->height)), "image height"},
              f->height);
  cmd->add_option("-o,--output", f->output,
                  "output image: .exr (float + metadata), .hdr, .pfm or .png (preview)")
      ->required();
  cmd->add_flag("--gpu", f->gpu,
                "render with OpenGL (headless EGL; the nn model only, docs/GPU.md) instead of the "
                "CPU");
  cmd->add_option("--preview", f->preview, "also write a tone-mapped PNG preview here");
  cmd->add_option("--false-colour", f->false_colour,
                  "also write a log-luminance false-colour PNG with legend here");
  add_numbers(
      *cmd,
      {"false-colour-range", "log10 cd/m^2", ParameterKind::numbers, -20.0, 20.0, 2,
       ParameterValue(f->fc_range), "log10 luminance range LO,HI of the false-colour scale"},
      f->fc_range);
  commands.push_back({cmd, [f, cmd] { return run_render(*f, *cmd); }});
}

}  // namespace skylight::cli
