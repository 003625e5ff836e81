// `skylight nn animate`: an environment-map sequence from a neural sky model (docs/NN.md) or a
// Pietras network (docs/PIETRAS.md: twilight included, from --observer-altitude): the sun moved
// from --from to --to (angles interpolated, the azimuth the short way round) or from --from-time
// to --to-time (times interpolated, the SPA at --lat/--lon), one image per frame through the
// render projections, each written atomically; --strip puts every frame side by side in one PNG
// with one exposure.
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <optional>

#include "common.h"
#include "nn_parts.h"
#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/numbers.h"
#include "skylight/io/file.h"
#include "skylight/io/image.h"
#include "skylight/models/neural_sky.h"
#include "skylight/models/pietras.h"
#include "skylight/render/sky_render.h"
#include "skylight/render/tonemap.h"
#include "skylight/sun/spa.h"
#include "skylight/sun/time.h"

namespace skylight::cli {
namespace {

struct AnimateFlags {
  std::string weights, output, strip;
  // Sky networks only (the sqrt(T) input), Pietras networks only (the density input).
  std::optional<double> turbidity, observer_altitude_m;
  std::vector<double> from, to;
  std::string from_time, to_time;
  std::optional<double> lat_deg, lon_deg;
  int frames = 10;
  std::string projection = "equirect";
  FisheyeFlags fisheye;
  int width = 1024, height = 512;
};

// PATTERN with its first run of '#' replaced by the zero-padded frame number.
std::string frame_path(const std::string& pattern, int frame, int frames) {
  const std::size_t a = pattern.find('#');
  const std::size_t b = pattern.find_first_not_of('#', a);
  const std::size_t run = (b == std::string::npos ? pattern.size() : b) - a;
  const std::size_t digits = std::max(run, fmt::format("{}", frames - 1).size());
  return pattern.substr(0, a) + fmt::format("{:0{}}", frame, digits) +
         (b == std::string::npos ? std::string() : pattern.substr(b));
}

// The sun of frame k of n (k / (n - 1) of the way).
SunPosition frame_sun(const AnimateFlags& f, int k, int n) {
  const double u = n > 1 ? static_cast<double>(k) / (n - 1) : 0.0;
  if (!f.from_time.empty()) {
    const sun::DateTime t0 = sun::parse_iso8601(f.from_time);
    const sun::DateTime t1 = sun::parse_iso8601(f.to_time);
    const double jd0 = sun::julian_day(t0), jd1 = sun::julian_day(t1);
    sun::SpaInput in;
    in.time = sun::date_time_from_julian_day(jd0 + u * (jd1 - jd0), t0.utc_offset_minutes, 3);
    in.latitude = deg_to_rad(*f.lat_deg);
    in.longitude = deg_to_rad(*f.lon_deg);
    const sun::SpaResult r = sun::solar_position(in);
    return {r.zenith, r.azimuth};
  }
  double da = std::remainder(f.to[1] - f.from[1], 360.0);  // the short way round
  const double zenith = f.from[0] + u * (f.to[0] - f.from[0]);
  return sun_from_degrees(zenith, f.from[1] + u * da);
}

int run_animate(const AnimateFlags& f) {
  const bool by_time = !f.from_time.empty() || !f.to_time.empty();
  if (by_time) {
    if (f.from_time.empty() || f.to_time.empty() || !f.from.empty() || !f.to.empty())
      throw InvalidArgument("give --from-time and --to-time, or --from and --to");
    if (!f.lat_deg || !f.lon_deg)
      throw InvalidArgument("--from-time/--to-time need --lat and --lon");
  } else if (f.from.empty() || f.to.empty()) {
    throw InvalidArgument(
        "give --from and --to (sun zenith,azimuth in deg), or --from-time and "
        "--to-time");
  }
  if (f.output.find('#') == std::string::npos)
    throw InvalidArgument(fmt::format(
        "-o '{}': the pattern needs a run of '#' for the frame number", excerpt(f.output)));
  (void)io::format_from_path(frame_path(f.output, 0, f.frames));
  if (!f.strip.empty() && io::format_from_path(f.strip) != io::ImageFormat::png)
    throw InvalidArgument(fmt::format("--strip '{}' must be a .png file", excerpt(f.strip)));
  render::RenderSettings s;
  s.projection = *parse_projection(f.projection);
  s.width = f.width;
  s.height = f.height;
  s.fisheye = f.fisheye.layout(kFisheyeFovDeg);
  validate(s);
  // A sky network or a Pietras network (read once; load_sky_network_file's checks on this text).
  const std::string text = io::read_text_file(f.weights);
  std::optional<nn::PietrasNetwork> pietras;
  nn::SkyNetwork network;
  if (nn::is_pietras_json(text)) {
    pietras = nn::pietras_from_json(text, f.weights);
    if (f.turbidity)
      throw InvalidArgument(fmt::format(
          "--turbidity: '{}' is a Pietras network, which has no turbidity input (its atmosphere "
          "is the training planet's)",
          excerpt(f.weights)));
  } else {
    network = nn::sky_network_from_json(text, f.weights);
    if (f.observer_altitude_m)
      throw InvalidArgument(
          fmt::format("--observer-altitude: '{}' is a sky network, which has no altitude input "
                      "(only Pietras networks take it)",
                      excerpt(f.weights)));
  }
  std::vector<SunPosition> suns;
  for (int k = 0; k < f.frames; ++k) suns.push_back(frame_sun(f, k, f.frames));

  Progress progress("nn animate");
  io::ImageF strip(f.strip.empty() ? 1 : s.width * f.frames, f.strip.empty() ? 1 : s.height, 3);
  std::string out;
  int dark = 0;
  for (int k = 0; k < f.frames; ++k) {
    progress(k, f.frames, fmt::format("frame {}", k));
    std::unique_ptr<SkyModel> model;
    if (pietras) {
      PietrasParameters p;
      p.sun = suns[k];
      p.weights = f.weights;
      if (f.observer_altitude_m) p.observer_altitude_m = *f.observer_altitude_m;
      model = std::make_unique<PietrasSkyModel>(p, *pietras);
    } else {
      NeuralSkyParameters p;
      p.sun = suns[k];
      p.weights = f.weights;
      if (f.turbidity) p.turbidity = *f.turbidity;
      model = std::make_unique<NeuralSkyModel>(p, network);
    }
    const SunPosition& sun = model->sun();
    const render::SkyImage img = render::render_sky(*model, s);
    for (float v : img.rgb.data)
      if (!std::isfinite(v))
        throw InvalidArgument(fmt::format("frame {}: the network gives a non-finite value", k));
    // A sky network was trained for suns above the horizon; a Pietras network covers twilight
    // and night (its shadow test).
    if (!pietras && sun.zenith > kPi / 2) ++dark;
    auto md = model_metadata(*model, "sky");
    md.emplace_back("skylight:projection", f.projection);
    md.emplace_back("skylight:frame", fmt::format("{} of {}", k, f.frames));
    const std::string path = frame_path(f.output, k, f.frames);
    render::write_image_or_preview(path, img.rgb, md);
    if (!f.strip.empty())
      for (int row = 0; row < s.height; ++row)
        for (int col = 0; col < s.width; ++col)
          std::copy_n(img.rgb.pixel(col, row), 3, strip.pixel(k * s.width + col, row));
    out += fmt::format("{:5}  {:14.3f}  {:15.3f}  {}\n", k, rad_to_deg(sun.zenith),
                       rad_to_deg(sun.azimuth), path);
  }
  progress(f.frames, f.frames, "done");
  if (dark > 0)
    warn(
        fmt::format("{} frames have the sun below the horizon (drawn black: the network was "
                    "trained for suns above it)",
                    dark));
  if (!f.strip.empty()) {
    render::write_image_or_preview(
        f.strip, strip,
        {{"Software", "skylight nn animate"},
         {"Comment", fmt::format("{} frames, left to right, one exposure", f.frames)}});
    out += fmt::format("strip: {}\n", f.strip);
  }
  write_stdout("frame  sun_zenith_deg  sun_azimuth_deg  file\n" + out);
  return kExitOk;
}

}  // namespace

void add_nn_animate_command(CLI::App& nn, Commands& commands) {
  auto f = std::make_shared<AnimateFlags>();
  auto* cmd = nn.add_subcommand(
      "animate",
      "an environment-map sequence of a neural sky or a Pietras network with the sun moving "
      "between two positions or times");
  cmd->add_option("--weights", f->weights,
                  "weights file (JSON): a sky network or a Pietras network")
      ->required();
  ParameterSpec turbidity = *NeuralSkyParameters::schema().find("turbidity");
  turbidity.default_value = Absent{"3; sky networks only"};
  add_number(*cmd, turbidity, f->turbidity);
  ParameterSpec altitude = *PietrasParameters::schema().find("observer-altitude");
  altitude.default_value = Absent{"0; Pietras networks only"};
  altitude.description = "observer above the ground, a Pietras network's density input";
  add_number(*cmd, altitude, f->observer_altitude_m);
  add_numbers(*cmd,
              {"from", "deg", ParameterKind::numbers, -360.0, 360.0, 2, Absent{"--from-time"},
               "the first frame's sun: zenith,azimuth"},
              f->from);
  add_numbers(*cmd,
              {"to", "deg", ParameterKind::numbers, -360.0, 360.0, 2, Absent{"--to-time"},
               "the last frame's sun: zenith,azimuth"},
              f->to);
  cmd->add_option("--from-time", f->from_time,
                  "the first frame's time, ISO 8601 with UTC offset (the sun by the SPA)");
  cmd->add_option("--to-time", f->to_time, "the last frame's time (times interpolated linearly)");
  ParameterSpec lat = sun::spa_parameter_spec("lat"), lon = sun::spa_parameter_spec("lon");
  lat.default_value = Absent{"needed with --from-time"};
  lon.default_value = Absent{"needed with --from-time"};
  add_number(*cmd, lat, f->lat_deg);
  add_number(*cmd, lon, f->lon_deg);
  add_integer(*cmd,
              {"frames", "1", ParameterKind::integer, 1, 100000, 1,
               ParameterValue(static_cast<double>(f->frames)), "number of frames"},
              f->frames);
  cmd->add_option("--projection", f->projection, "equirect|hemisphere|fisheye; default equirect")
      ->check(CLI::IsMember({"equirect", "hemisphere", "fisheye"}));
  f->fisheye.add(*cmd, "180", "fisheye: field of view across the image circle");
  add_integer(*cmd,
              {"width", "px", ParameterKind::integer, 1, kMaxImageSide, 1,
               ParameterValue(static_cast<double>(f->width)), "image width"},
              f->width);
  add_integer(*cmd,
              {"height", "px", ParameterKind::integer, 1, kMaxImageSide, 1,
               ParameterValue(static_cast<double>(f->height)), "image height"},
              f->height);
  cmd->add_option("-o,--output", f->output,
                  "frame files: a pattern whose run of '#' becomes the zero-padded frame number, "
                  ".exr (float + metadata), .hdr, .pfm or .png (preview)")
      ->required();
  cmd->add_option("--strip", f->strip,
                  "also write every frame side by side into this PNG (one exposure for all)");
  commands.push_back({cmd, [f] { return run_animate(*f); }});
}

}  // namespace skylight::cli
