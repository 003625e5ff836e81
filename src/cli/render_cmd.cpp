// `skylight render`: a sky model into an image (EXR, HDR, PFM or a PNG preview by extension), with
// optional tone-mapped preview and log-luminance false-colour map. `--gpu` renders the `nn` model
// with the headless GL module instead (gpu/sky_render.h, docs/GPU.md).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common.h"
#include "skylight/core/error.h"
#include "skylight/io/image.h"
#include "skylight/operations/operations.h"
#include "skylight/render/false_colour.h"
#include "skylight/render/sky_render.h"
#include "skylight/render/tonemap.h"
#ifdef SKYLIGHT_HAVE_GPU
#include "skylight/gpu/sky_render.h"
#endif

namespace skylight::cli {
namespace {

struct RenderCommand {
  ModelOptions model;
  SchemaFlags flags;  // the image, false-colour and --gpu parameters of operations "render"
  std::string output, preview, false_colour;
};

// The image options of `render`: every projection, 1024 x 512 by default.
const ImageSchemaOptions kImage{};

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

int run_render(const RenderCommand& f) {
  const ParameterValues given = f.flags.values();
  const ImageOptions image = f.flags.bind(image_schema(kImage), kImage.defaults(), "render");
  render::RenderSettings s;
  static_cast<Camera&>(s) = image.camera();
  s.sun = f.model.sun_mode();
  if (const auto unread = image.unread(given); !unread.empty()) {
    std::string list;
    for (const auto& n : unread) list += (list.empty() ? "--" : ", --") + n;
    warn(fmt::format("{} not used by --projection {}; ignored", list, to_string(image.projection)));
  }
  (void)io::format_from_path(f.output);
  if (!f.preview.empty() && io::format_from_path(f.preview) != io::ImageFormat::png)
    throw InvalidArgument(fmt::format("--preview '{}' must be a .png file", f.preview));
  if (!f.false_colour.empty() && io::format_from_path(f.false_colour) != io::ImageFormat::png)
    throw InvalidArgument(fmt::format("--false-colour '{}' must be a .png file", f.false_colour));
  const auto fc = f.flags.bind(render::FalseColourOptions::schema(), {}, "render");
  const bool gpu = given.has("gpu");
  const auto model = f.model.make();
  warn_domain(*model);
  const render::SkyImage img = gpu ? render_on_gpu(*model, s) : render::render_sky(*model, s);
  // No output may hold NaN or Inf: a model that overflows is an error, and nothing is written.
  const auto bad = std::count_if(img.rgb.data.begin(), img.rgb.data.end(),
                                 [](float v) { return !std::isfinite(v); });
  if (bad > 0)
    throw InvalidArgument(fmt::format(
        "model '{}' gives {} non-finite pixel values (overflow) with these parameters; nothing "
        "was written",
        model->name(), bad));

  auto md = model_metadata(*model, to_string(s.sun));
  for (auto& entry : f.model.solar_position_metadata()) md.push_back(std::move(entry));
  const auto layout = image.metadata();
  md.push_back(layout.front());  // the projection
  if (gpu) md.emplace_back("skylight:renderer", "gpu (OpenGL fragment shader, docs/GPU.md)");
  md.insert(md.end(), layout.begin() + 1, layout.end());
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
    const render::FalseColourOptions& fo = fc;
    io::write_png(f.false_colour, render::false_colour(lum, fo, &img.mask),
                  with_pixel_unit(md, fmt::format("false colour of log10 luminance, {} to {} "
                                                  "log10 cd/m^2 (legend in the image)",
                                                  fo.log10_min, fo.log10_max)));
  }
  return kExitOk;
}

}  // namespace

void add_render_command(CLI::App& app, Commands& commands) {
  auto f = std::make_shared<RenderCommand>();
  auto* cmd = app.add_subcommand("render",
                                 "render a sky into an image (EXR, HDR, PFM or PNG by extension)");
  f->model.add(*cmd);
  f->flags.add(*cmd, operations::without_model_specs(operations::find("render")));
  cmd->add_option("-o,--output", f->output,
                  "output image: .exr (float + metadata), .hdr, .pfm or .png (preview)")
      ->required();
  cmd->add_option("--preview", f->preview, "also write a tone-mapped PNG preview here");
  cmd->add_option("--false-colour", f->false_colour,
                  "also write a log-luminance false-colour PNG with legend here");
  commands.push_back({cmd, [f] { return run_render(*f); }});
}

}  // namespace skylight::cli
