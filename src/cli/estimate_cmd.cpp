// `skylight estimate`: the turbidity of a clear sky from an HDR photograph (fisheye or equirect),
// by fitting a model whose registry entry declares an EstimationPolicy (Preetham, Hosek-Wilkie, the
// CIE standard sky types) to luminance samples of the photo (estimate/photo.h,
// fit/luminance_fit.h); docs/ESTIMATE.md.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "common.h"
#include "skylight/core/camera.h"
#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/estimate/capture.h"
#include "skylight/estimate/photo.h"
#include "skylight/fit/luminance_fit.h"
#include "skylight/io/camera_calibration.h"
#include "skylight/io/image.h"
#include "skylight/operations/operations.h"
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

struct EstimateCommand {
  std::string image, mask, compare;
  bool json = false;
  SchemaFlags flags;  // the operation's parameters (operations::find("estimate"))
};

// The fitted values, their fit's quality and (ranking) the ranking, into JSON and text.
void describe_fit(const std::string& model, const EstimationPolicy& policy,
                  const fit::LuminanceFit& fit, const fit::EstimateSettings& es,
                  nlohmann::ordered_json& j, std::string& text) {
  const bool ranking = policy.method == EstimationPolicy::Method::ranking;
  j["model"] = model;
  text += fmt::format("model            {}\n", model);
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
  if (!ranking) return;
  {
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
}

int run_estimate(const EstimateCommand& c) {
  const SchemaFlags& f = c.flags;
  const ParameterValues given = f.values();
  const io::ImageF image = io::read_image(c.image);
  const ImageSchemaOptions photo = estimate::photo_image_options();
  const ImageOptions layout = f.bind(image_schema(photo), photo.defaults(), "estimate");
  warn_unread_layout(layout, given);
  const auto co = f.bind(estimate::CaptureOptions::schema(), {}, "estimate");
  std::optional<estimate::Capture> capture;
  if (!co.exif.empty())
    capture = estimate::read_capture(co, image.width);
  else if (!co.utc_offset.empty())
    warn("--utc-offset is not read without --exif; ignored");
  std::optional<io::ImageF> user_mask;
  if (!c.mask.empty()) user_mask = estimate::load_mask(c.mask);
  if (!c.compare.empty() && io::format_from_path(c.compare) != io::ImageFormat::png)
    throw InvalidArgument(fmt::format("--compare '{}' must be a .png file", excerpt(c.compare)));
  // The pipeline is the library's (operations::estimate_photo), shared with the Python package.
  const operations::PhotoEstimate pe =
      operations::estimate_photo(image, given, user_mask ? &*user_mask : nullptr, capture);
  const estimate::PhotoSamples& ps = pe.samples;
  const fit::LuminanceFit& fit = pe.fit;
  const fit::EstimateSettings& es = pe.settings;
  const std::string& model = pe.model;
  const EstimationPolicy& policy = fit::estimation_policy(model);
  const double zenith_deg = rad_to_deg(ps.sun.zenith), azimuth_deg = rad_to_deg(ps.sun.azimuth);
  nlohmann::ordered_json j;
  std::string text;
  describe_fit(model, policy, fit, es, j, text);
  if (!c.compare.empty())
    write_comparison(c.compare, image, ps.mask, fit::fitted_luminance_image(fit, pe.camera));
  const char* sun_text = pe.sun_source.c_str();
  j["sun_zenith_deg"] = zenith_deg;
  j["sun_azimuth_deg"] = azimuth_deg;
  j["sun_source"] = sun_text;
  j["samples"] = ps.samples.size();
  j["sky_pixels"] = ps.sky_pixels;
  if (!layout.calibration.empty()) j["calibration"] = layout.calibration;
  if (capture) {
    const io::ExifInfo& e = capture->exif;
    auto& x = j["exif"] = nlohmann::ordered_json::object();
    x["file"] = co.exif;
    x["camera"] = fmt::format("{}{}{}", e.make, e.make.empty() ? "" : " ", e.model);
    const auto or_null = [](const auto& v) { return v ? nlohmann::ordered_json(*v) : nullptr; };
    x["date_time"] = or_null(e.date_time);
    x["utc_offset"] = or_null(e.utc_offset);
    x["focal_length_mm"] = or_null(e.focal_length_mm);
    x["focal_length_px"] = or_null(capture->focal_length_px);
    x["latitude_deg"] = or_null(e.latitude_deg);
    x["longitude_deg"] = or_null(e.longitude_deg);
    text += fmt::format(
        "exif             {}{}{}{}\n", e.date_time.value_or("no time"),
        e.utc_offset ? " " + *e.utc_offset : "",
        e.focal_length_mm ? fmt::format(", focal length {:g} mm", *e.focal_length_mm) : "",
        e.latitude_deg && e.longitude_deg
            ? fmt::format(", GPS {:.5f}, {:.5f}", *e.latitude_deg, *e.longitude_deg)
            : "");
  }
  j["ransac"] = es.ransac;
  j["seed"] = es.seed;
  text += fmt::format("sun              zenith {:.3f} deg, azimuth {:.3f} deg ({})\n", zenith_deg,
                      azimuth_deg, sun_text);
  text += fmt::format("sky pixels       {}\n", ps.sky_pixels);
  // No output may hold NaN or Inf (a photo with absurd values could overflow the scale).
  for (const auto& [key, value] : j.items())
    if (value.is_number_float() && !std::isfinite(value.get<double>()))
      throw InvalidArgument(fmt::format("the fit gave a non-finite {}; nothing was written", key));
  // Paths in other encodings than UTF-8: replaced, not an exception.
  write_stdout(c.json
                   ? j.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n"
                   : text);
  return kExitOk;
}

}  // namespace

void add_estimate_command(CLI::App& app, Commands& commands) {
  auto c = std::make_shared<EstimateCommand>();
  const OperationInfo& op = operations::find("estimate");
  auto* cmd = app.add_subcommand(
      "estimate",
      "turbidity (or CIE sky type) of a clear sky from an HDR photo\n"
      "Turbidity of a clear sky from an HDR photo, fisheye or equirect: a Preetham, Hosek-Wilkie "
      "or CIE sky-type fit (Morales et al. 2017; docs/ESTIMATE.md).");
  cmd->add_option("--image", c->image, "the sky photo: linear .exr, .hdr or .pfm")->required();
  cmd->add_option("--mask", c->mask,
                  "sky mask (.png, .pfm, .exr, .hdr) of the image's size: nonzero = sky");
  c->flags.add(*cmd, op.parameters);
  wire_solar_position(c->flags, {"sun-zenith", "sun-azimuth"}, false);
  cmd->add_option("--compare", c->compare,
                  "write a .png: the photo's luminance (sky pixels) beside the fitted sky, false "
                  "colour on one log scale");
  cmd->add_flag("--json", c->json, "write JSON instead of labelled lines");
  commands.push_back({cmd, [c] { return run_estimate(*c); }});
}

}  // namespace skylight::cli
