// `estimate`: the turbidity of a clear sky (or another model's fitted parameters) from an HDR
// photo (Morales et al. 2017; docs/ESTIMATE.md): the pipeline is estimate_photo (operations.h);
// here its declaration, the comparison image and the record.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "skylight/core/math.h"
#include "skylight/estimate/capture.h"
#include "skylight/estimate/photo.h"
#include "skylight/fit/luminance_fit.h"
#include "skylight/io/camera_calibration.h"
#include "skylight/operations/detail/families.h"
#include "skylight/operations/operations.h"
#include "skylight/render/false_colour.h"

namespace skylight::operations::detail {
namespace {

// --compare: the photo's luminance (non-sky pixels grey) beside the fitted sky, one false-colour
// scale spanning the sky pixels' 1st to 99th percentile in whole decades.
io::Image8 comparison(const io::ImageF& image, const estimate::SkyMask& mask,
                      const io::ImageF& fitted) {
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
  return both;
}

struct EstimateResult {
  PhotoEstimate pe{};
  std::string calibration{};
  std::optional<estimate::Capture> capture{};
  std::string exif_file{};
};

// A fitted axis's record key: its parameter's name with '_' ("cie-type": "cie_type").
std::string key_of(const std::string& parameter) {
  std::string k = parameter;
  std::replace(k.begin(), k.end(), '-', '_');
  return k;
}

struct Ranked {
  int value = 0;
  double inlier_fraction = 0.0, residual = 0.0;
};

struct ExifRecord {
  std::string file{}, camera{};
  std::optional<std::string> date_time{}, utc_offset{};
  std::optional<double> focal_length_mm{}, focal_length_px{}, latitude_deg{}, longitude_deg{};
};

const ResultSchema<ExifRecord>& exif_record() {
  using X = ExifRecord;
  static const ResultSchema<X> s = [] {
    ResultSchema<X> s;
    s.text("file", "the capture's EXIF file", &X::file)
        .text("camera", "make and model", &X::camera)
        .text("date_time", "DateTimeOriginal", &X::date_time)
        .text("utc_offset", "OffsetTimeOriginal", &X::utc_offset)
        .number("focal_length_mm", "mm", "FocalLength", &X::focal_length_mm)
        .number("focal_length_px", "px", "the focal length in the photo's pixels",
                &X::focal_length_px)
        .number("latitude_deg", "deg", "GPS latitude", &X::latitude_deg)
        .number("longitude_deg", "deg", "GPS longitude", &X::longitude_deg);
    return s;
  }();
  return s;
}

using EstimateSchema = ResultSchema<EstimateResult>;

// The fitted parameters of every model with an estimation policy (registry order; null for the
// other models), a turbidity always (null when the model fitted has none).
void add_fitted_parameters(EstimateSchema& s) {
  using R = EstimateResult;
  std::set<std::string> keys;
  const auto fitted = [](const std::string& parameter, bool sigma) {
    return [parameter, sigma](const R& r) -> std::optional<double> {
      for (const fit::FittedParameter& p : r.pe.fit.parameters)
        if (p.name == parameter) return sigma ? p.sigma : p.value;
      return std::nullopt;
    };
  };
  bool turbidity = false;
  for (const ModelInfo& m : model_registry()) {
    if (!m.estimation) continue;
    for (const EstimationPolicy::Axis& a : m.estimation->axes) {
      const std::string key = key_of(a.parameter);
      if (!keys.insert(key).second) continue;
      turbidity = turbidity || a.parameter == "turbidity";
      if (m.estimation->method == EstimationPolicy::Method::ranking) {
        s.integer(key, "1", fmt::format("{} (the best ranked; {})", a.label, m.name),
                  [parameter = a.parameter](const R& r) -> std::optional<long long> {
                    for (const fit::FittedParameter& p : r.pe.fit.parameters)
                      if (p.name == parameter) return std::lround(p.value);
                    return std::nullopt;
                  });
      } else {
        s.number(key, "1", fmt::format("{} ({})", a.label, m.name), fitted(a.parameter, false), 4)
            .number(key + "_sigma", "1",
                    fmt::format("its standard deviation over bootstrap resamples ({})", m.name),
                    fitted(a.parameter, true), 4);
      }
    }
  }
  SKYLIGHT_CHECK(turbidity, "an estimation policy fits the turbidity");
}

// Each ranking policy's list of every value it ranked.
void add_rankings(EstimateSchema& s) {
  for (const ModelInfo& m : model_registry()) {
    if (!m.estimation || m.estimation->method != EstimationPolicy::Method::ranking) continue;
    ResultSchema<Ranked> ranked;
    ranked.integer(m.estimation->ranking_key, "1", "the value", &Ranked::value)
        .number("inlier_fraction", "1", "inliers / samples at it", &Ranked::inlier_fraction, 3)
        .number("residual", "1", "RMS of ln luminance", &Ranked::residual, 5);
    s.records(m.estimation->ranking_field,
              fmt::format("every value, best first ({}; empty for the other models)", m.name),
              ranked, [name = m.name](const EstimateResult& r) {
                std::vector<Ranked> out;
                if (r.pe.model == name)
                  for (const fit::RankedValue& v : r.pe.fit.ranking)
                    out.push_back({static_cast<int>(v.value), v.inlier_fraction, v.residual});
                return out;
              });
  }
}

// The sun, the samples, the calibration and the EXIF the fit used.
void add_inputs(EstimateSchema& s) {
  using R = EstimateResult;
  s.number(
       "sun_zenith_deg", "deg", "the sun used",
       [](const R& r) { return rad_to_deg(r.pe.samples.sun.zenith); }, 3)
      .number(
          "sun_azimuth_deg", "deg", "from north towards east",
          [](const R& r) { return rad_to_deg(r.pe.samples.sun.azimuth); }, 3)
      .text("sun_source", "given, time, exif or image", [](const R& r) { return r.pe.sun_source; })
      .integer("samples", "1", "sky pixels sampled",
               [](const R& r) { return static_cast<long long>(r.pe.samples.samples.size()); })
      .integer("sky_pixels", "1", "pixels of the sky mask",
               [](const R& r) { return static_cast<long long>(r.pe.samples.sky_pixels); })
      .text("calibration", "the camera calibration file, if one was given",
            [](const R& r) -> std::optional<std::string> {
              if (r.calibration.empty()) return std::nullopt;
              return r.calibration;
            })
      .nested("exif", "what the capture's EXIF held (with --exif)", exif_record(),
              [](const R& r) -> std::optional<ExifRecord> {
                if (!r.capture) return std::nullopt;
                const io::ExifInfo& e = r.capture->exif;
                return ExifRecord{r.exif_file,
                                  fmt::format("{}{}{}", e.make, e.make.empty() ? "" : " ", e.model),
                                  e.date_time,
                                  e.utc_offset,
                                  e.focal_length_mm,
                                  r.capture->focal_length_px,
                                  e.latitude_deg,
                                  e.longitude_deg};
              })
      .flag("ransac", "clouds rejected by RANSAC", [](const R& r) { return r.pe.settings.ransac; })
      .integer("seed", "1", "of the sampling, RANSAC and bootstrap",
               [](const R& r) { return static_cast<long long>(r.pe.settings.seed); });
}

// The record's fields: the model, its fitted parameters, the fit's quality, the rankings and
// what the fit used.
const EstimateSchema& estimate_result() {
  using R = EstimateResult;
  static const EstimateSchema s = [] {
    EstimateSchema s;
    s.text("model", "the model fitted", [](const R& r) { return r.pe.model; });
    add_fitted_parameters(s);
    s.number(
         "inlier_fraction", "1", "inliers / samples",
         [](const R& r) { return r.pe.fit.inlier_fraction; }, 3)
        .number(
            "residual", "1", "RMS of ln luminance over the inliers",
            [](const R& r) { return r.pe.fit.residual; }, 5)
        .integer("inliers", "1", "samples the fit kept",
                 [](const R& r) { return r.pe.fit.inliers; })
        .text("method", "levenberg-marquardt, bracketing or ranking",
              [](const R& r) { return r.pe.fit.method; })
        .number("luminance_scale", "1", "s: the photo's Y = s x the model's luminance",
                [](const R& r) { return std::exp(r.pe.fit.log_scale); });
    add_rankings(s);
    add_inputs(s);
    return s;
  }();
  return s;
}

Result run_estimate(const Request& r) {
  const io::ImageF image = r.image("image");
  const ImageSchemaOptions photo = estimate::photo_image_options();
  const ImageOptions layout = r.bind(image_schema(photo), photo.defaults());
  const auto co = r.bind(estimate::CaptureOptions::schema());
  EstimateResult er;
  er.calibration = layout.calibration;
  er.exif_file = co.exif;
  if (!co.exif.empty()) er.capture = estimate::read_capture(co, image.width);
  std::optional<io::ImageF> user_mask;
  if (r.frontend().images.count("mask"))
    user_mask = r.image("mask");
  else if (r.given("mask"))
    user_mask = estimate::load_mask(*r.text("mask"));
  er.pe = estimate_photo(image, r.values(), user_mask ? &*user_mask : nullptr, er.capture);
  Result out;
  if (r.output_wanted("compare"))
    r.write_png(
        out, "compare",
        comparison(image, er.pe.samples.mask, fit::fitted_luminance_image(er.pe.fit, er.pe.camera)),
        {{"Software", "skylight estimate"}, {"Comment", "photo | fitted sky"}});
  out.record = estimate_result().record(er);
  return out;
}

OperationInfo estimate_operation() {
  OperationInfo op{
      .name = "estimate",
      .summary = "turbidity (or CIE sky type) of a clear sky from an HDR photo",
      .description =
          "the turbidity of a clear sky (or another model's fitted parameters) from an HDR "
          "photo, fisheye or equirect: the sun (given, from a time, or found), the sky mask, "
          "random sky samples and the fit (Morales et al. 2017; docs/ESTIMATE.md)",
      .parameters = concat(
          {{input_file("image", "the sky photo: linear .exr, .hdr or .pfm", kFloatImageFormats),
            input_file("mask", "sky mask of the image's size: nonzero = sky", kImageFormats,
                       "the automatic mask")},
           {fit::estimation_model_spec()},
           image_schema(estimate::photo_image_options()).specs(),
           sun_specs("from --time, or found in the image"),
           solar_position_specs("the sun from the angles, the EXIF time (--exif), or found in "
                                "the image"),
           estimate::CaptureOptions::schema().specs(),
           estimate::MaskSettings::schema().specs(),
           fit::EstimateSettings::schema().specs(),
           {output_file("compare",
                        "a PNG of the photo's luminance (sky pixels) beside the fitted sky, false "
                        "colour on one log scale",
                        kPngFormat, "none")}}),
      .relations = {needs("sun-zenith", "sun-azimuth"), needs("sun-azimuth", "sun-zenith"),
                    excludes("time", "sun-zenith", "time gives the sun"),
                    excludes("time", "sun-azimuth", "time gives the sun"),
                    unread_without("utc-offset", "exif")},
      .result = estimate_result().fields(),
      .result_type = "fit::LuminanceFit"};
  for (ParameterSpec& s : op.parameters)
    if (s.name == "exif" || s.name == "calibration") s.file = FileRole::input;
  op.check = [](Request& r) {
    const ImageSchemaOptions photo = estimate::photo_image_options();
    const ImageOptions layout = r.bind(image_schema(photo), photo.defaults());
    for (const std::string& name : layout.unread(r.values())) {
      r.warn(fmt::format("{} is not read ({}); ignored", spelled(name),
                         layout.calibration.empty()
                             ? "not a parameter of this projection"
                             : spelled(layout.calibration_flag) + " gives the layout"));
      r.drop(name);
    }
    if (!r.given("time") && !r.given("exif"))
      for (const auto& spec : sun::spa_parameter_specs())
        if (r.given(spec.name))
          throw InvalidArgument(fmt::format("{} needs {}, or {} with an EXIF time",
                                            spelled(spec.name), spelled("time"), spelled("exif")));
    // The model's policy and the fit settings, before the photo is read.
    (void)fit::estimation_policy(r.text("model").value_or(fit::default_estimated_model()));
    (void)r.bind(fit::EstimateSettings::schema());
    (void)r.bind(estimate::MaskSettings::schema());
  };
  op.run = [](const Request& r, const ProgressSink&) { return run_estimate(r); };
  return op;
}

}  // namespace

std::vector<OperationInfo> estimate_operations() {
  return {estimate_operation()};
}

}  // namespace skylight::operations::detail
