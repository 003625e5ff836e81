// `skylight estimate`: the turbidity of a clear sky from an HDR photograph (fisheye or equirect),
// by fitting the Preetham model (estimate/turbidity.h) or the Hosek-Wilkie model
// (estimate/hosek_fit.h) to luminance samples, or the best CIE standard sky type
// (estimate/sky_type.h); docs/ESTIMATE.md.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "common.h"
#include "skylight/core/camera.h"
#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/estimate/photo.h"
#include "skylight/fit/luminance_fit.h"
#include "skylight/io/image.h"
#include "skylight/render/false_colour.h"
#include "skylight/sun/spa.h"

namespace skylight::cli {
namespace {

// --compare: the photo's luminance (non-sky pixels grey) beside the fitted sky, one false-colour
// scale spanning the sky pixels' 1st to 99th percentile in whole decades.
void write_comparison(const std::string& path, const io::ImageF& image,
                      const estimate::SkyMask& mask, const io::ImageF& fitted) {
  const io::ImageF photo = estimate::photo_luminance_image(image);
  std::vector<double> logs;
  std::vector<std::uint8_t> outside(mask.sky.size());
  for (std::size_t i = 0; i < mask.sky.size(); ++i) {
    outside[i] = mask.sky[i] ? 0 : 1;
    if (mask.sky[i]) logs.push_back(std::log10(photo.data[i]));
  }
  std::sort(logs.begin(), logs.end());
  render::FalseColourOptions fo;
  fo.unit = "photo units";
  fo.log10_min = std::floor(logs[logs.size() / 100]);
  fo.log10_max = std::max(fo.log10_min + 1.0, std::ceil(logs[logs.size() - 1 - logs.size() / 100]));
  const io::Image8 left = render::false_colour(photo, fo, &outside);
  const io::Image8 right = render::false_colour(fitted, fo);
  constexpr int kGap = 8;
  io::Image8 both(left.width + kGap + right.width, std::max(left.height, right.height));
  for (int row = 0; row < both.height; ++row)
    for (int col = 0; col < both.width; ++col) {
      std::uint8_t* p = both.pixel(col, row);
      const io::Image8* src = col < left.width           ? &left
                              : col >= left.width + kGap ? &right
                                                         : nullptr;
      const int c = col < left.width ? col : col - left.width - kGap;
      if (src && row < src->height)
        std::copy_n(src->pixel(c, row), 3, p);
      else
        std::fill_n(p, 3, std::uint8_t{255});
    }
  io::write_png(path, both, {{"Software", "skylight estimate"}, {"Comment", "photo | fitted sky"}});
}

struct EstimateFlags {
  std::string image, mask, compare;
  std::string projection = "fisheye";
  FisheyeFlags fisheye;
  std::optional<double> sun_zenith_deg, sun_azimuth_deg;
  SpaOptions spa;
  std::string model = fit::default_estimated_model();
  int samples = 100, seed = 1, ransac_iterations = 64, bootstrap = 32;
  double inlier_threshold = 0.1;
  double min_elevation_deg = 0.0, sun_exclusion_deg = 5.0;
  bool no_ransac = false, json = false;
};

int run_estimate(const EstimateFlags& f) {
  if (f.sun_zenith_deg.has_value() != f.sun_azimuth_deg.has_value())
    throw InvalidArgument("--sun-zenith and --sun-azimuth go together");
  const io::ImageF image = io::read_image(f.image);
  const Camera camera =
      image_camera(*parse_projection(f.projection), f.fisheye.layout(), image.width, image.height);
  std::optional<io::ImageF> user_mask;
  if (!f.mask.empty()) user_mask = estimate::load_mask(f.mask);
  if (!f.compare.empty() && io::format_from_path(f.compare) != io::ImageFormat::png)
    throw InvalidArgument(fmt::format("--compare '{}' must be a .png file", excerpt(f.compare)));

  // The sun: given angles, the solar position of --time/--lat/--lon, or found in the image.
  std::optional<SunPosition> given_sun;
  std::string sun_source = "image";
  if (f.sun_zenith_deg) {
    given_sun = sun_from_degrees(*f.sun_zenith_deg, *f.sun_azimuth_deg);
    sun_source = "given";
  } else if (f.spa.given()) {
    const sun::SpaResult r = sun::solar_position(f.spa.input());
    given_sun = sun_from_degrees(rad_to_deg(r.zenith), rad_to_deg(r.azimuth));
    sun_source = "time";
  }
  estimate::MaskSettings ms;
  ms.min_elevation = deg_to_rad(f.min_elevation_deg);
  ms.sun_exclusion = deg_to_rad(f.sun_exclusion_deg);
  fit::EstimateSettings es;
  es.samples = f.samples;
  es.seed = static_cast<std::uint64_t>(f.seed);
  es.ransac = !f.no_ransac;
  es.ransac_iterations = f.ransac_iterations;
  es.inlier_threshold = f.inlier_threshold;
  es.bootstrap = f.bootstrap;
  const EstimationPolicy& policy = fit::estimation_policy(f.model);
  const estimate::PhotoSamples ps = estimate::sample_photo(
      image, camera, given_sun, ms, es.samples, es.seed, user_mask ? &*user_mask : nullptr);
  const fit::LuminanceFit fit = fit::fit_luminance(f.model, ps.samples, ps.sun, es);
  const double zenith_deg = rad_to_deg(ps.sun.zenith), azimuth_deg = rad_to_deg(ps.sun.azimuth);
  const bool ranking = policy.method == EstimationPolicy::Method::ranking;
  nlohmann::ordered_json j;
  std::string text;
  j["model"] = f.model;
  text += fmt::format("model            {}\n", f.model);
  for (std::size_t a = 0; a < policy.axes.size(); ++a) {
    const EstimationPolicy::Axis& axis = policy.axes[a];
    const fit::FittedParameter& p = fit.parameters[a];
    std::string key = p.name;
    std::replace(key.begin(), key.end(), '-', '_');
    if (ranking) {
      j[key] = static_cast<int>(p.value);
      text += fmt::format("{:<17}{} {}\n", axis.label, static_cast<int>(p.value), axis.note);
    } else {
      j[key] = p.value;
      j[key + "_sigma"] = p.sigma;
      // The method is said where the fit can fall back from LM (a profile scan's bracketing).
      const bool method = policy.method == EstimationPolicy::Method::profile_scan;
      text += fmt::format("{:<17}{:.4f} +- {:.4f}{}\n", axis.label, p.value, p.sigma,
                          method ? fmt::format(" ({})", fit.method) : "");
    }
  }
  // Every estimate reports a turbidity: null when the model fitted has none.
  if (!j.contains("turbidity")) {
    j["turbidity"] = nullptr;
    j["turbidity_sigma"] = nullptr;
  }
  j["inlier_fraction"] = fit.inlier_fraction;
  j["residual"] = fit.residual;
  j["inliers"] = fit.inliers;
  if (!ranking) j["method"] = fit.method;
  j["luminance_scale"] = std::exp(fit.log_scale);
  text += fmt::format("inliers          {} of {} samples ({:.3f}){}\n", fit.inliers, fit.samples,
                      fit.inlier_fraction, es.ransac || ranking ? "" : ", RANSAC off");
  text += fmt::format("residual         {:.5f} (RMS of ln luminance)\n", fit.residual);
  if (!f.compare.empty())
    write_comparison(f.compare, image, ps.mask, fit::fitted_luminance_image(fit, camera));
  if (ranking) {
    auto& list = j[policy.ranking_field] = nlohmann::ordered_json::array();
    text += "ranking          ";
    for (const fit::RankedValue& r : fit.ranking) {
      list.push_back({{policy.ranking_key, static_cast<int>(r.value)},
                      {"inlier_fraction", r.inlier_fraction},
                      {"residual", r.residual}});
      text +=
          fmt::format("{}{}", static_cast<int>(r.value), &r == &fit.ranking.back() ? "\n" : " ");
    }
  }
  const char* sun_text = ps.sun_detected ? "image" : sun_source.c_str();
  j["sun_zenith_deg"] = zenith_deg;
  j["sun_azimuth_deg"] = azimuth_deg;
  j["sun_source"] = sun_text;
  j["samples"] = ps.samples.size();
  j["sky_pixels"] = ps.sky_pixels;
  j["ransac"] = es.ransac;
  j["seed"] = f.seed;
  text += fmt::format("sun              zenith {:.3f} deg, azimuth {:.3f} deg ({})\n", zenith_deg,
                      azimuth_deg, sun_text);
  text += fmt::format("sky pixels       {}\n", ps.sky_pixels);
  // No output may hold NaN or Inf (a photo with absurd values could overflow the scale).
  for (const auto& [key, value] : j.items())
    if (value.is_number_float() && !std::isfinite(value.get<double>()))
      throw InvalidArgument(fmt::format("the fit gave a non-finite {}; nothing was written", key));
  write_stdout(f.json ? j.dump(2) + "\n" : text);
  return kExitOk;
}

}  // namespace

void add_estimate_command(CLI::App& app, Commands& commands) {
  auto f = std::make_shared<EstimateFlags>();
  auto* cmd = app.add_subcommand(
      "estimate",
      "turbidity of a clear sky from an HDR photo (fisheye or equirect; Preetham, Hosek-Wilkie or "
      "CIE sky-type fit)");
  cmd->add_option("--image", f->image, "the sky photo: linear .exr, .hdr or .pfm")->required();
  cmd->add_option("--mask", f->mask,
                  "sky mask (.png, .pfm, .exr, .hdr) of the image's size: nonzero = sky");
  cmd->add_option("--projection", f->projection, "fisheye|equirect; default fisheye")
      ->check(CLI::IsMember({"fisheye", "equirect"}));
  f->fisheye.add(*cmd, "180", "fisheye: field of view across the image circle");
  ParameterSpec zenith = sun_parameter_specs()[0], azimuth = sun_parameter_specs()[1];
  zenith.default_value = Absent{"from --time, or found in the image"};
  azimuth.default_value = Absent{"from --time, or found in the image"};
  auto* z = add_number(*cmd, zenith, f->sun_zenith_deg);
  auto* a = add_number(*cmd, azimuth, f->sun_azimuth_deg);
  auto* t =
      f->spa.add(*cmd, false, {"lat", "lon", "elevation", "pressure", "temperature", "delta-t"});
  t->excludes(z)->excludes(a);
  std::string models;
  for (const std::string& m : fit::estimated_models())
    models += fmt::format("{}{} ({})", models.empty() ? "" : ", ", m,
                          fit::estimation_policy(m).description);
  cmd->add_option(
         "--model", f->model,
         fmt::format("the model fitted: {}; default {}", models, fit::default_estimated_model()))
      ->check(CLI::IsMember(fit::estimated_models()));
  add_integer(*cmd,
              {"samples", "1", ParameterKind::integer, 2, 1000000, 1,
               ParameterValue(static_cast<double>(f->samples)),
               "random sky pixels per estimate (N of Morales 2017 eq. 8)"},
              f->samples);
  add_integer(
      *cmd,
      {"seed", "1", ParameterKind::integer, 0, 2147483647, 1,
       ParameterValue(static_cast<double>(f->seed)), "seed of the sampling, RANSAC and bootstrap"},
      f->seed);
  add_integer(*cmd,
              {"ransac-iterations", "1", ParameterKind::integer, 1, 100000, 1,
               ParameterValue(static_cast<double>(f->ransac_iterations)),
               "random minimal sets RANSAC tries"},
              f->ransac_iterations);
  add_number(
      *cmd,
      {"inlier-threshold", "1", ParameterKind::number, 1e-6, 10.0, 1,
       ParameterValue(f->inlier_threshold), "RANSAC: |ln Y - ln model| below this is clear sky"},
      f->inlier_threshold);
  add_integer(*cmd,
              {"bootstrap", "1", ParameterKind::integer, 0, 10000, 1,
               ParameterValue(static_cast<double>(f->bootstrap)),
               "bootstrap resamples of the inliers for turbidity_sigma (0: none)"},
              f->bootstrap);
  add_number(*cmd,
             {"min-elevation", "deg", ParameterKind::number, 0.0, 89.0, 1,
              ParameterValue(f->min_elevation_deg), "mask: ignore sky below this elevation"},
             f->min_elevation_deg);
  add_number(
      *cmd,
      {"sun-exclusion", "deg", ParameterKind::number, 0.0, 90.0, 1,
       ParameterValue(f->sun_exclusion_deg), "mask: ignore pixels within this angle of the sun"},
      f->sun_exclusion_deg);
  cmd->add_option("--compare", f->compare,
                  "write a .png: the photo's luminance (sky pixels) beside the fitted sky, false "
                  "colour on one log scale");
  cmd->add_flag("--no-ransac", f->no_ransac, "fit all samples (no outlier rejection)");
  cmd->add_flag("--json", f->json, "write JSON instead of labelled lines");
  commands.push_back({cmd, [f] { return run_estimate(*f); }});
}

}  // namespace skylight::cli
