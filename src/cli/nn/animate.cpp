// `skylight nn animate`: an environment-map sequence from a neural sky model (docs/NN.md) or a
// Pietras network (docs/PIETRAS.md: twilight included, from --observer-altitude), the sun moved
// between two positions or times (render/animation.h), one image per frame, each written in the
// command's transaction; --strip puts every frame side by side in one PNG with one exposure.
#include <fmt/format.h>

#include <cmath>
#include <memory>

#include "nn.h"
#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/io/image.h"
#include "skylight/models/pietras.h"
#include "skylight/operations/operations.h"
#include "skylight/render/animation.h"
#include "skylight/render/sky_render.h"
#include "skylight/render/tonemap.h"

namespace skylight::cli {
namespace {

struct AnimateCommand {
  SchemaFlags flags;
  std::string weights, output, strip;
};

int run_animate(const AnimateCommand& c) {
  const auto a =
      c.flags.bind(render::AnimationOptions::schema(), render::AnimationOptions{}, "nn animate");
  a.validate();
  (void)io::format_from_path(render::frame_path(c.output, 0, a.frames));
  if (!c.strip.empty() && io::format_from_path(c.strip) != io::ImageFormat::png)
    throw InvalidArgument(fmt::format("--strip '{}' must be a .png file", excerpt(c.strip)));
  render::RenderSettings s;
  static_cast<Camera&>(s) = a.image.camera();
  const ParameterValues given = c.flags.values();
  const std::optional<double> turbidity = given.number("turbidity");
  const std::optional<double> altitude = given.number("observer-altitude");
  // A sky network or a Pietras network, read once.
  const NetworkFile file = read_network_file(c.weights);
  // The option the file's kind does not read is refused before any frame.
  (void)network_model(file, c.weights, a.frame_sun(0), turbidity, altitude);

  Progress progress("nn animate");
  io::ImageF strip(c.strip.empty() ? 1 : s.width * a.frames, c.strip.empty() ? 1 : s.height, 3);
  std::string out;
  int dark = 0;
  for (int k = 0; k < a.frames; ++k) {
    progress(k, a.frames, fmt::format("frame {}", k));
    const auto model = network_model(file, c.weights, a.frame_sun(k), turbidity, altitude);
    const SunPosition& sun = model->sun();
    const render::SkyImage img = render::render_sky(*model, s);
    for (float v : img.rgb.data)
      if (!std::isfinite(v))
        throw InvalidArgument(fmt::format("frame {}: the network gives a non-finite value", k));
    // A sky network was trained for suns above the horizon; a Pietras network covers twilight
    // and night (its shadow test).
    if (!file.pietras && sun.zenith > kPi / 2) ++dark;
    auto md = model_metadata(*model, "sky");
    md.emplace_back("skylight:projection", std::string(to_string(a.image.projection)));
    md.emplace_back("skylight:frame", fmt::format("{} of {}", k, a.frames));
    const std::string path = render::frame_path(c.output, k, a.frames);
    render::write_image_or_preview(path, img.rgb, md);
    if (!c.strip.empty())
      for (int row = 0; row < s.height; ++row)
        for (int col = 0; col < s.width; ++col)
          std::copy_n(img.rgb.pixel(col, row), 3, strip.pixel(k * s.width + col, row));
    out += fmt::format("{:5}  {:14.3f}  {:15.3f}  {}\n", k, rad_to_deg(sun.zenith),
                       rad_to_deg(sun.azimuth), path);
  }
  progress(a.frames, a.frames, "done");
  if (dark > 0)
    warn(
        fmt::format("{} frames have the sun below the horizon (drawn black: the network was "
                    "trained for suns above it)",
                    dark));
  if (!c.strip.empty()) {
    render::write_image_or_preview(
        c.strip, strip,
        {{"Software", "skylight nn animate"},
         {"Comment", fmt::format("{} frames, left to right, one exposure", a.frames)}});
    out += fmt::format("strip: {}\n", c.strip);
  }
  write_stdout("frame  sun_zenith_deg  sun_azimuth_deg  file\n" + out);
  return kExitOk;
}

}  // namespace

void add_nn_animate_command(CLI::App& nn, Commands& commands) {
  auto c = std::make_shared<AnimateCommand>();
  auto* cmd = nn.add_subcommand(
      "animate",
      "environment maps of a network's sky with the sun moving\n"
      "An environment-map sequence of a neural sky or a Pietras network with the sun moving "
      "between two positions or times.");
  cmd->add_option("--weights", c->weights,
                  "weights file (JSON): a sky network or a Pietras network")
      ->required();
  c->flags.add(*cmd, operations::find("nn animate").parameters);
  cmd->add_option("-o,--output", c->output,
                  "frame files: a pattern whose run of '#' becomes the zero-padded frame number, "
                  ".exr (float + metadata), .hdr, .pfm or .png (preview)")
      ->required();
  cmd->add_option("--strip", c->strip,
                  "also write every frame side by side into this PNG (one exposure for all)");
  commands.push_back({cmd, [c] { return run_animate(*c); }});
}

}  // namespace skylight::cli
