// `sh fit|eval|export|render|error`: SH polynomial tables (Habel, Mustata & Wimmer 2008;
// docs/SH.md) fitted to any registry model, evaluated, exported, rendered and measured; the work
// is fit/sh_fit.h's, models/sh.h's and sh/'s.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <memory>

#include "skylight/core/math.h"
#include "skylight/fit/sh_fit.h"
#include "skylight/models/sh.h"
#include "skylight/operations/detail/families.h"
#include "skylight/operations/operations.h"
#include "skylight/render/sky_render.h"
#include "skylight/sh/basis.h"
#include "skylight/sh/irradiance.h"

namespace skylight::operations::detail {
namespace {

std::vector<std::string> channel_names(sh::Channels c) {
  return c == sh::Channels::xyz ? std::vector<std::string>{"X", "Y", "Z"}
                                : std::vector<std::string>{"r", "g", "b"};
}

// The table of a request: in memory (a front end's), the --table file, or the embedded default.
std::shared_ptr<const sh::PolynomialTable> table_of(const Request& r) {
  if (const auto it = r.frontend().texts.find("table"); it != r.frontend().texts.end())
    return std::make_shared<const sh::PolynomialTable>(
        sh::table_from_json(it->second, "the " + spelled("table")));
  return std::make_shared<const sh::PolynomialTable>(load_sh_table(r.text("table").value_or("")));
}

// The sh model of the sun, table, bands, filter and tau given.
std::unique_ptr<ShSkyModel> sh_model(const Request& r) {
  ShParameters p = r.bind(ShParameters::schema());
  p.sun = sun_from_degrees(r.number("sun-zenith").value_or(kDefaultSunZenithDeg),
                           r.number("sun-azimuth").value_or(kDefaultSunAzimuthDeg));
  return std::make_unique<ShSkyModel>(p, table_of(r));
}

// The table as a record (what it holds).
struct TableRecord {
  const sh::PolynomialTable* t = nullptr;
  std::optional<double> seconds{};
};

const ResultSchema<TableRecord>& table_result() {
  using R = TableRecord;
  static const ResultSchema<R> s = [] {
    ResultSchema<R> s;
    s.text("model", "the model fitted", [](const R& r) { return r.t->model; })
        .text("parameter", "its second axis tau (null: the sun zenith only)",
              [](const R& r) -> std::optional<std::string> {
                if (r.t->parameter.empty()) return std::nullopt;
                return r.t->parameter;
              })
        .text("channels", "xyz or linear-srgb",
              [](const R& r) { return r.t->channels == sh::Channels::xyz ? "xyz" : "linear-srgb"; })
        .integer("bands", "1", "SH bands", [](const R& r) { return r.t->bands; })
        .integer("degree_theta", "1", "the polynomial's degree in the sun zenith axis",
                 [](const R& r) { return r.t->degree_theta; })
        .integer("degree_tau", "1", "its degree in tau", [](const R& r) { return r.t->degree_tau; })
        .integer("coefficients", "1", "coefficients of the table",
                 [](const R& r) { return static_cast<long long>(r.t->coefficients.size()); })
        .integer("bytes", "B", "their memory in float",
                 [](const R& r) { return static_cast<long long>(r.t->bytes()); })
        .number("seconds", "s", "the fit's wall time", &R::seconds, 1);
    return s;
  }();
  return s;
}

OperationInfo sh_fit_operation() {
  OperationInfo op{.name = "sh fit",
                   .summary = "fit an SH polynomial table to a registry model",
                   .description =
                       "an SH polynomial table (Habel et al. 2008 eq. 1) fitted to a registry "
                       "model's converged projections; the model's fit policy gives tau, its range "
                       "and the table's structure (docs/SH.md)",
                   .parameters = concat({fit::ShFitRequest::schema().specs(),
                                         {output_file("output", "the table file (JSON)", {})}}),
                   .result = table_result().fields(),
                   .result_type = "sh::PolynomialTable"};
  for (ParameterSpec& s : op.parameters)
    if (s.name == "model") s.default_value = Required{};
  op.check = [](Request& r) { (void)fit::sh_fit_settings(r.bind(fit::ShFitRequest::schema())); };
  op.run = [](const Request& r, const ProgressSink&) {
    fit::ShFitSettings s = fit::sh_fit_settings(r.bind(fit::ShFitRequest::schema()));
    const auto t0 = std::chrono::steady_clock::now();
    s.polynomial.progress = [&](int done, int total) {
      r.progress(done, total, fmt::format("projections of '{}'", s.model));
    };
    const sh::PolynomialTable t = fit::fit_sh_table(s);
    Result out;
    r.write_text(out, "output", sh::table_to_json(t));
    out.record = table_result().record(
        {&t, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()});
    return out;
  };
  return op;
}

// ---- eval ---------------------------------------------------------------------------------------

struct ShCoefficient {
  int l = 0, m = 0;
  std::vector<double> values{};
};

struct ShEvalResult {
  std::string fitted_model{}, channels{}, quantity{};
  std::vector<std::string> channel_names{};
  int bands = 0;
  bool ringing_filter = false;
  double sun_zenith_deg = 0.0, sun_azimuth_deg = 0.0;
  std::optional<double> turbidity{};
  std::vector<ShCoefficient> coefficients{};
};

const ResultSchema<ShEvalResult>& sh_eval_result() {
  using R = ShEvalResult;
  static const ResultSchema<R> s = [] {
    ResultSchema<ShCoefficient> c;
    c.integer("l", "1", "degree", &ShCoefficient::l)
        .integer("m", "1", "order", &ShCoefficient::m)
        .numbers("values", "", "the coefficient per channel (channel_names)",
                 &ShCoefficient::values);
    ResultSchema<R> s;
    s.text("fitted_model", "the model the table was fitted to", &R::fitted_model)
        .text("channels", "xyz or linear_srgb", &R::channels)
        .texts("channel_names", "the channels' names, in the values' order", &R::channel_names)
        .text("quantity", "radiance, or irradiance (--irradiance)", &R::quantity)
        .integer("bands", "1", "SH bands", &R::bands)
        .flag("ringing_filter", "the ringing filter applied (eq. 5)", &R::ringing_filter)
        .number("sun_zenith_deg", "deg", "the sun's zenith angle", &R::sun_zenith_deg)
        .number("sun_azimuth_deg", "deg", "the sun's azimuth", &R::sun_azimuth_deg)
        .number("turbidity", "1", "the table's second parameter, when it has one", &R::turbidity)
        .records("coefficients", "one per (l, m), index l (l + 1) + m", c, &R::coefficients);
    return s;
  }();
  return s;
}

OperationInfo sh_eval_operation() {
  OperationInfo op{.name = "sh eval",
                   .summary = "SH coefficients of the sky for a sun and turbidity",
                   .description =
                       "the SH coefficients of a table's sky (eq. 1, rotation eq. 4, "
                       "ringing filter eq. 5), or of its irradiance",
                   .parameters = concat({sun_parameter_specs(), ShParameters::schema().specs(),
                                         ShEvalOptions::schema().specs()}),
                   .result = sh_eval_result().fields(),
                   .result_type = "sh::Coefficients"};
  for (ParameterSpec& s : op.parameters)
    if (s.name == "table") s.file = FileRole::input;
  op.run = [](const Request& r, const ProgressSink&) {
    const auto model = sh_model(r);
    const bool irradiance = r.bind(ShEvalOptions::schema()).irradiance;
    const sh::Coefficients co =
        irradiance ? model->irradiance_coefficients() : model->coefficients();
    ShEvalResult e{
        .fitted_model = model->table().model,
        .channels = model->table().channels == sh::Channels::xyz ? "xyz" : "linear_srgb",
        .quantity = irradiance ? "irradiance" : "radiance",
        .channel_names = channel_names(model->table().channels),
        .bands = co.bands,
        // The irradiance convolves the unfiltered radiance (ShSkyModel::irradiance_coefficients).
        .ringing_filter = !irradiance && !model->parameters().no_ringing_filter,
        .sun_zenith_deg = rad_to_deg(model->sun().zenith),
        .sun_azimuth_deg = rad_to_deg(model->sun().azimuth),
        .turbidity = model->parameters().turbidity};
    for (int i = 0; i < sh::coefficient_count(co.bands); ++i) {
      const auto [l, m] = sh::degree_order(i);
      const auto& v = co.c[static_cast<std::size_t>(i)];
      e.coefficients.push_back({l, m, {v[0], v[1], v[2]}});
    }
    Result out;
    out.record = sh_eval_result().record(e);
    return out;
  };
  return op;
}

// ---- export, render -----------------------------------------------------------------------------

OperationInfo sh_export_operation() {
  OperationInfo op{.name = "sh export",
                   .summary = "write a table as a C header (or JSON)",
                   .description = "a table as JSON or as a C header",
                   .parameters = concat({{*ShParameters::schema().find("table")},
                                         sh::ExportOptions::schema().specs(),
                                         {output_file("output", "the file written")}}),
                   .relations = {needs("monomial", "c-header")},
                   .result = table_result().fields(),
                   .result_type = "text"};
  for (ParameterSpec& s : op.parameters)
    if (s.name == "table") s.file = FileRole::input;
  op.run = [](const Request& r, const ProgressSink&) {
    const auto t = table_of(r);
    Result out;
    r.write_text(out, "output", sh::export_table(*t, r.bind(sh::ExportOptions::schema())));
    out.record = table_result().record({t.get(), std::nullopt});
    return out;
  };
  return op;
}

// Display images (.png) are clamped at 0; float files keep the unclamped reconstruction.
io::ImageF for_format(const Request& r, std::string_view output, io::ImageF img) {
  const std::string path = r.output_path(output);
  if (!path.empty() && io::format_from_path(path) == io::ImageFormat::png)
    for (float& v : img.data) v = std::max(v, 0.0f);
  return img;
}

struct ShRenderResult {
  int width = 0, height = 0;
  std::string fitted_model{};
};

const ResultSchema<ShRenderResult>& sh_render_result() {
  using R = ShRenderResult;
  static const ResultSchema<R> s = [] {
    ResultSchema<R> s;
    s.text("fitted_model", "the model the table was fitted to", &R::fitted_model)
        .integer("width", "px", "the environment map's width", &R::width)
        .integer("height", "px", "its height", &R::height);
    return s;
  }();
  return s;
}

OperationInfo sh_render_operation() {
  OperationInfo op{
      .name = "sh render",
      .summary = "the reconstructed sky as an env map; a diffuse sphere lit by it",
      .description =
          "a table's sky as an equirect environment map, and a diffuse sphere lit by "
          "it (--sphere)",
      .parameters = concat(
          {sun_parameter_specs(),
           ShParameters::schema().specs(),
           ShRenderOptions::schema().specs(),
           sh::SphereOptions::schema().specs(),
           {output_file("output", "the environment map (.exr/.hdr/.pfm; .png clamped at 0)",
                        kImageFormats),
            output_file("sphere", "a diffuse sphere lit by the SH sky", kImageFormats, "none")}}),
      .result = sh_render_result().fields(),
      .result_type = "render::SkyImage, and the sphere's linear sRGB image"};
  for (ParameterSpec& s : op.parameters)
    if (s.name == "table") s.file = FileRole::input;
  for (const char* name : {"sphere-size", "sphere-albedo"})
    op.relations.push_back(unread_without(name, "sphere"));
  op.run = [](const Request& r, const ProgressSink&) {
    const auto model = sh_model(r);
    const int width = r.bind(ShRenderOptions::schema()).width;
    const auto sphere = r.bind(sh::SphereOptions::schema());
    render::RenderSettings s;
    s.projection = Projection::equirect;
    s.width = width;
    s.height = width / 2;
    validate(s);
    const render::SkyImage img = render::render_sky(*model, s);
    auto md = model_metadata(*model, "sky");
    md.emplace_back("skylight:projection", "equirect");
    md.emplace_back("skylight:pixel_unit",
                    "linear sRGB (D65), Y = luminance [cd/m^2]; SH reconstruction, unclamped in "
                    "float files, clamped at 0 in PNG");
    Result out;
    r.write_image(out, "output", for_format(r, "output", img.rgb), md);
    if (r.output_wanted("sphere")) {
      auto smd = md;
      smd.emplace_back("skylight:sphere_albedo", fmt::format("{}", sphere.albedo));
      r.write_image(out, "sphere",
                    for_format(r, "sphere",
                               sh::diffuse_sphere(model->irradiance_coefficients(),
                                                  model->table().channels, sphere)),
                    smd);
    }
    out.record = sh_render_result().record({s.width, s.height, model->table().model});
    return out;
  };
  return op;
}

// ---- error --------------------------------------------------------------------------------------

struct ShErrorRecord {
  int bands = 0;
  std::string channel{};
  double e_mean_worst = 0, e_mean_median = 0, e_max_worst = 0, e_max_median = 0;
  double worst_sun_zenith_deg = 0, worst_tau = 0;
};

struct ShErrorResult {
  std::string model{};
  int degree_theta = 0, degree_tau = 0, points = 0;
  std::vector<ShErrorRecord> rows{};
};

const ResultSchema<ShErrorResult>& sh_error_result() {
  using R = ShErrorResult;
  static const ResultSchema<R> s = [] {
    using E = ShErrorRecord;
    ResultSchema<E> row;
    row.integer("bands", "1", "N: bands reconstructed", &E::bands)
        .text("channel", "the channel", &E::channel)
        .number("e_mean_worst_percent", "%", "E_mean (eq. 3), worst over the points",
                &E::e_mean_worst, 5)
        .number("e_mean_median_percent", "%", "E_mean, median", &E::e_mean_median, 5)
        .number("e_max_worst_percent", "%", "E_max (eq. 2), worst", &E::e_max_worst, 5)
        .number("e_max_median_percent", "%", "E_max, median", &E::e_max_median, 5)
        .number("worst_sun_zenith_deg", "deg", "where E_mean is worst", &E::worst_sun_zenith_deg, 2)
        .number("worst_tau", "1", "and its tau", &E::worst_tau, 3);
    ResultSchema<R> s;
    s.text("model", "the model fitted", &R::model)
        .integer("degree_theta", "1", "the table's degree in the sun zenith", &R::degree_theta)
        .integer("degree_tau", "1", "its degree in tau", &R::degree_tau)
        .integer("points", "1", "the (sun zenith, tau) points measured", &R::points)
        .records("rows", "per band count and channel", row, &R::rows);
    return s;
  }();
  return s;
}

OperationInfo sh_error_operation() {
  OperationInfo op{.name = "sh error",
                   .summary = "a table's reconstruction errors per band count",
                   .description =
                       "E_mean (Habel et al. 2008 eq. 3) and E_max (eq. 2) of a table "
                       "per band count, worst and median over the table's suns and "
                       "turbidities",
                   .parameters = concat({{*ShParameters::schema().find("table")},
                                         fit::ShErrorOptions::schema().specs()}),
                   .result = sh_error_result().fields(),
                   .result_type = "fit::ShTableError"};
  for (ParameterSpec& s : op.parameters)
    if (s.name == "table") s.file = FileRole::input;
  op.run = [](const Request& r, const ProgressSink&) {
    const auto t = table_of(r);
    const fit::ShTableError e =
        fit::table_error(*t, r.bind(fit::ShErrorOptions::schema()),
                         [&](int done, int total) { r.progress(done, total, "projections"); });
    const auto names = channel_names(t->channels);
    ShErrorResult er{t->model, t->degree_theta, t->degree_tau, e.points, {}};
    for (const fit::ShErrorRow& row : e.rows)
      er.rows.push_back({row.bands, names[static_cast<std::size_t>(row.channel)],
                         100 * row.e_mean_worst, 100 * row.e_mean_median, 100 * row.e_max_worst,
                         100 * row.e_max_median, rad_to_deg(row.worst_theta), row.worst_tau});
    Result out;
    out.record = sh_error_result().record(er);
    return out;
  };
  return op;
}

}  // namespace

std::vector<OperationInfo> sh_operations() {
  return {sh_fit_operation(), sh_eval_operation(), sh_export_operation(), sh_render_operation(),
          sh_error_operation()};
}

}  // namespace skylight::operations::detail
