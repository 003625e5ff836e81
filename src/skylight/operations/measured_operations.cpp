// `measured`: a sky model fitted to each measured clear sky of Kider et al. 2014 and its errors
// (fit/measured_fit.h; docs/MEASURED.md): the declaration, the CSV of the samples and the record.
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "skylight/core/math.h"
#include "skylight/core/statistics.h"
#include "skylight/fit/measured_fit.h"
#include "skylight/io/file.h"
#include "skylight/io/kider.h"
#include "skylight/operations/detail/families.h"

namespace skylight::operations::detail {
namespace {

using fit::MeasuredCaptureResult;
using fit::MeasuredSampleResult;

struct MeasuredResult {
  std::string model, source, sun_azimuth_from;
  double exclude_sun_deg = 0.0;
  std::vector<MeasuredCaptureResult> captures;
};

struct Fitted {
  std::string name;
  double value = 0.0;
};

const ResultSchema<MeasuredSampleResult>& sample_record() {
  using S = MeasuredSampleResult;
  static const ResultSchema<S> s = [] {
    ResultSchema<S> s;
    s.integer("index", "1", "the scan's sample index (0-80; 0 is its ring neighbours' mean)",
              [](const S& x) { return static_cast<long long>(x.index); })
        .number("zenith_deg", "deg", "view zenith angle", &S::zenith_deg, 4)
        .number("azimuth_deg", "deg", "view azimuth from north towards east", &S::azimuth_deg, 4)
        .number("measured_luminance", "cd/m^2", "683 x the integral of L y-bar, 380-780 nm",
                &S::measured_luminance, 2)
        .number("model_luminance", "cd/m^2", "the fitted model's, without the scale",
                &S::model_luminance, 2)
        .flag("used", "outside --exclude-sun-deg of the sun", &S::used);
    return s;
  }();
  return s;
}

const ResultSchema<MeasuredCaptureResult>& capture_record() {
  using C = MeasuredCaptureResult;
  static const ResultSchema<C> s = [] {
    ResultSchema<Fitted> fitted;
    fitted.text("name", "the model's parameter", &Fitted::name)
        .number("value", "1", "its fitted value", &Fitted::value, 4);
    ResultSchema<C> s;
    s.text("name", "the capture (its folder's name: local date and time)", &C::name)
        .number(
            "sun_zenith_deg", "deg", "the SPA's at the capture's time",
            [](const C& c) { return rad_to_deg(c.sun.sun.zenith); }, 3)
        .number(
            "sun_azimuth_deg", "deg", "the sun used, from north towards east",
            [](const C& c) { return rad_to_deg(c.sun.sun.azimuth); }, 3)
        .number(
            "spa_sun_azimuth_deg", "deg", "the SPA's at the capture's time",
            [](const C& c) { return rad_to_deg(c.sun.spa_azimuth); }, 3)
        .records("parameters", "the model's fitted parameters", fitted,
                 [](const C& c) {
                   std::vector<Fitted> out;
                   for (const fit::FittedParameter& p : c.fit.parameters)
                     out.push_back({p.name, p.value});
                   return out;
                 })
        .number("scale", "1", "the best single factor: measured ~ scale x model", &C::scale, 4)
        .number("luminance_rms_shape", "1", "relative RMS of the luminance after the scale",
                &C::luminance_rms_shape, 4)
        .number("luminance_rms_abs", "1", "relative RMS of the luminance without the scale",
                &C::luminance_rms_abs, 4)
        .number("spectral_rms", "1",
                "relative RMS of the spectral radiance after the scale, 380-780 nm (null: the "
                "model has no spectra)",
                &C::spectral_rms, 4)
        .number("mean_delta_uv", "1", "mean CIE 1976 u'v' distance of the chromaticities",
                &C::mean_delta_uv, 5)
        .number("global_horizontal_model_w_m2", "W/m^2",
                "the model's global horizontal irradiance (null: no broadband spectrum)",
                &C::global_horizontal_model_w_m2, 1)
        .number("global_horizontal_measured_w_m2", "W/m^2",
                "the pyranometer's mean during the scan (null: no pyranometer file)",
                &C::global_horizontal_measured_w_m2, 1)
        .integer("samples_used", "1", "samples outside --exclude-sun-deg of the sun",
                 [](const C& c) { return static_cast<long long>(c.samples_used); })
        .records("samples", "every direction of the scan", sample_record(), &C::samples);
    return s;
  }();
  return s;
}

// The median of a capture field over the captures.
template <class G>
double median_of(const MeasuredResult& r, G get) {
  std::vector<double> v;
  for (const auto& c : r.captures) v.push_back(get(c));
  return median(v);
}

const ResultSchema<MeasuredResult>& measured_result() {
  using R = MeasuredResult;
  static const ResultSchema<R> s = [] {
    ResultSchema<R> s;
    s.text("model", "the model fitted", &R::model)
        .text("kider", "the captures read", &R::source)
        .text("sun_azimuth_from", "spa or symmetry", &R::sun_azimuth_from)
        .number("exclude_sun_deg", "deg", "samples nearer the sun are not used",
                &R::exclude_sun_deg)
        .number(
            "median_luminance_rms_shape", "1", "over the captures",
            [](const R& r) {
              return median_of(
                  r, [](const MeasuredCaptureResult& c) { return c.luminance_rms_shape; });
            },
            4)
        .number(
            "median_luminance_rms_abs", "1", "over the captures",
            [](const R& r) {
              return median_of(r,
                               [](const MeasuredCaptureResult& c) { return c.luminance_rms_abs; });
            },
            4)
        .number(
            "median_scale", "1", "over the captures",
            [](const R& r) {
              return median_of(r, [](const MeasuredCaptureResult& c) { return c.scale; });
            },
            4)
        .records("captures", "one per capture, by name", capture_record(), &R::captures);
    return s;
  }();
  return s;
}

std::string samples_csv(const MeasuredResult& r) {
  std::string out =
      "capture,index,zenith_deg,azimuth_deg,measured_luminance_cd_m2,model_luminance_cd_m2,"
      "scaled_model_luminance_cd_m2,used\n";
  for (const auto& c : r.captures)
    for (const auto& s : c.samples)
      out += fmt::format("{},{},{:.6f},{:.6f},{:.9g},{:.9g},{:.9g},{}\n", c.name, s.index,
                         s.zenith_deg, s.azimuth_deg, s.measured_luminance, s.model_luminance,
                         c.scale * s.model_luminance, s.used ? 1 : 0);
  return out;
}

Result run_measured(const Request& r, const ProgressSink& progress) {
  const auto settings = r.bind(fit::MeasuredSettings::schema());
  MeasuredResult mr;
  mr.model = settings.model;
  mr.exclude_sun_deg = settings.exclude_sun_deg;
  mr.sun_azimuth_from =
      settings.sun_azimuth == fit::SunAzimuthSource::symmetry ? "symmetry" : "spa";
  std::vector<io::KiderCapture> captures;
  if (const auto dir = r.text("kider")) {
    captures = io::read_kider(*dir);
    mr.source = *dir;
  } else {
    captures = io::shipped_kider_subset();
    mr.source = fmt::format("data/{} (shipped)", io::kKiderSubsetDataDir);
  }
  mr.captures = fit::compare_to_measured(captures, settings, progress);
  Result out;
  if (r.output_wanted("output")) r.write_text(out, "output", samples_csv(mr));
  out.record = measured_result().record(mr);
  return out;
}

OperationInfo measured_operation() {
  OperationInfo op{
      .name = "measured",
      .summary = "sky models fitted to measured clear skies (Kider et al. 2014)",
      .description =
          "a sky model's free parameters fitted to each measured clear sky of Kider et al. 2014 "
          "(81 directions, spectral radiance, a pyranometer), and its errors in shape, absolute "
          "level, spectrum and colour (docs/MEASURED.md)",
      .parameters = concat(
          {{ParameterSpec{.name = "kider",
                          .unit = "",
                          .kind = ParameterKind::text,
                          .default_value = Absent{"the shipped subset, data/measured/kider2014/"},
                          .description = "a folder of Kider et al. 2014's captures (the data "
                                         "set, a date, its RADIANCE folder or one capture) or "
                                         "of the shipped subset"}},
           fit::MeasuredSettings::schema().specs(),
           {output_file("output",
                        "every sample of every capture as CSV (measured and model luminance)",
                        {".csv"}, "no CSV")}}),
      .relations = {},
      .result = measured_result().fields(),
      .result_type = "fit::MeasuredCaptureResult per capture"};
  op.check = [](Request& r) {
    (void)r.bind(fit::MeasuredSettings::schema()).site();
    check_input_folder(r, "kider");
  };
  op.run = [](const Request& r, const ProgressSink& progress) { return run_measured(r, progress); };
  return op;
}

}  // namespace

std::vector<OperationInfo> measured_operations() {
  return {measured_operation()};
}

}  // namespace skylight::operations::detail
