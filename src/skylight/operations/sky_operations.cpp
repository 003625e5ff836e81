// `render` (a sky model into an image, with a tone-mapped preview and a false-colour map; `--gpu`
// by the installed GL backend) and `eval` (a model in given directions, CSV).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "skylight/core/camera.h"
#include "skylight/core/math.h"
#include "skylight/io/directions.h"
#include "skylight/models/evaluation.h"
#include "skylight/operations/detail/families.h"
#include "skylight/operations/gpu_backend.h"
#include "skylight/operations/operations.h"
#include "skylight/render/false_colour.h"
#include "skylight/render/sky_render.h"

namespace skylight::operations::detail {

// The relations of the sun and the solar disc (model_specs()).
std::vector<Relation> model_relations() {
  std::vector<Relation> r{excludes("sun-zenith", "sun-elevation")};
  for (const Relation& s : solar_position_relations({"sun-zenith", "sun-elevation", "sun-azimuth"}))
    r.push_back(s);
  r.push_back(excludes("include-sun", "sun-only"));
  return r;
}

namespace {

// ---- render -------------------------------------------------------------------------------------

// The image options of `render`: every projection, 1024 x 512 by default.
const ImageSchemaOptions kRenderImage{};

// What the pixels of each output are (skylight:pixel_unit).
constexpr const char* kFloatPixelUnit = "linear sRGB (D65), Y = luminance [cd/m^2]";
constexpr const char* kPreviewPixelUnit =
    "tone-mapped display values (8-bit sRGB: 99th percentile of luminance -> 1, Reinhard, sRGB "
    "curve), not luminance";

// A copy of `md` whose skylight:pixel_unit is `unit`.
io::Metadata with_pixel_unit(io::Metadata md, const std::string& unit) {
  for (auto& [key, value] : md)
    if (key == "skylight:pixel_unit") value = unit;
  return md;
}

struct RenderResult {
  std::string model{}, projection{}, sun{}, renderer{}, domain{};
  int width = 0, height = 0;
  double sun_zenith_deg = 0.0, sun_azimuth_deg = 0.0, zenith_luminance = 0.0;
};

const ResultSchema<RenderResult>& render_result() {
  using R = RenderResult;
  static const ResultSchema<R> s = [] {
    ResultSchema<R> s;
    s.text("model", "the sky model", &R::model)
        .text("projection", "the image's layout", &R::projection)
        .integer("width", "px", "image width", &R::width)
        .integer("height", "px", "image height", &R::height)
        .number("sun_zenith_deg", "deg", "the sun's zenith angle", &R::sun_zenith_deg)
        .number("sun_azimuth_deg", "deg", "the sun's azimuth from north towards east",
                &R::sun_azimuth_deg)
        .text("sun", "what is drawn: sky, sky+sun or sun-only", &R::sun)
        .number("zenith_luminance_cd_m2", "cd/m^2", "the model's luminance at the zenith",
                &R::zenith_luminance)
        .text("domain", "where the model stands: valid, extrapolated, unphysical or undefined",
              &R::domain)
        .text("renderer", "cpu (the batch path on all threads) or gpu", &R::renderer);
    return s;
  }();
  return s;
}

void warn_domain(const Request& r, const SkyModel& model, bool spectral) {
  for (const auto& issue : model.domain().issues)
    if (spectral || !issue.spectral_only)
      r.warn(fmt::format("{} ({}): {}", model.name(), to_string(issue.validity), issue.message));
}

Result run_render(const Request& r) {
  const ImageOptions image = r.bind(image_schema(kRenderImage), kRenderImage.defaults());
  render::RenderSettings s;
  static_cast<Camera&>(s) = image.camera();
  s.sun = r.bind(SolarDisc::schema()).mode;
  const bool gpu = r.given("gpu");
  const auto model = make_sky(r);
  warn_domain(r, *model, false);
  const render::SkyImage img =
      gpu ? gpu_backend("--gpu").render_sky(*model, s) : render::render_sky(*model, s);
  // No output may hold NaN or Inf: a model that overflows is an error, and nothing is written.
  const auto bad = std::count_if(img.rgb.data.begin(), img.rgb.data.end(),
                                 [](float v) { return !std::isfinite(v); });
  if (bad > 0)
    throw InvalidArgument(fmt::format(
        "model '{}' gives {} non-finite pixel values (overflow) with these parameters; nothing "
        "was written",
        model->name(), bad));
  RenderResult rr{.model = std::string(model->name()),
                  .projection = std::string(to_string(image.projection)),
                  .sun = std::string(to_string(s.sun)),
                  .renderer = gpu ? "gpu" : "cpu",
                  .domain = std::string(to_string(model->domain().worst())),
                  .width = s.width,
                  .height = s.height,
                  .sun_zenith_deg = rad_to_deg(model->sun().zenith),
                  .sun_azimuth_deg = rad_to_deg(model->sun().azimuth),
                  .zenith_luminance = model->tristimulus({0.0, 0.0, 1.0}).Y};
  auto md = model_metadata(*model, rr.sun);
  if (const auto spa = solar_position_input(r.values()))
    for (auto& entry : solar_position_metadata(*spa)) md.push_back(std::move(entry));
  const auto layout = image.metadata();
  md.push_back(layout.front());  // the projection
  if (gpu) md.emplace_back("skylight:renderer", "gpu (OpenGL fragment shader, docs/GPU.md)");
  md.insert(md.end(), layout.begin() + 1, layout.end());
  md.emplace_back("skylight:pixel_unit", kFloatPixelUnit);
  // What the model actually used: its zenith luminance and where it stands in its domain.
  md.emplace_back("skylight:zenith_luminance_evaluated_cd_m2",
                  fmt::format("{}", rr.zenith_luminance));
  md.emplace_back("skylight:domain", rr.domain);
  Result out;
  const bool output_is_png =
      r.given("output") && io::format_from_path(r.output_path("output")) == io::ImageFormat::png;
  r.write_image(out, "output", img.rgb,
                output_is_png ? with_pixel_unit(md, kPreviewPixelUnit) : md);
  r.write_image(out, "preview", img.rgb, with_pixel_unit(md, kPreviewPixelUnit));
  if (r.output_wanted("false-colour")) {
    io::ImageF lum(img.xyz.width, img.xyz.height, 1);
    for (std::size_t i = 0; i < lum.data.size(); ++i) lum.data[i] = img.xyz.data[3 * i + 1];
    const auto fo = r.bind(render::FalseColourOptions::schema());
    r.write_png(out, "false-colour", render::false_colour(lum, fo, &img.mask),
                with_pixel_unit(md, fmt::format("false colour of log10 luminance, {} to {} "
                                                "log10 cd/m^2 (legend in the image)",
                                                fo.log10_min, fo.log10_max)));
  }
  out.record = render_result().record(rr);
  return out;
}

OperationInfo render_operation() {
  OperationInfo op{
      .name = "render",
      .summary = "render a sky into an image (EXR, HDR, PFM or PNG by extension)",
      .description =
          "a sky model drawn into an image in one of the project's layouts (the batch path on "
          "all threads, or the network models by GL); the chosen model's own parameters are its "
          "registry entry's (`skylight models`)",
      .parameters =
          concat({model_specs(),
                  image_schema(kRenderImage).specs(),
                  render::FalseColourOptions::schema().specs(),
                  {gpu_spec("render with OpenGL (headless EGL; the network models nn and pietras, "
                            "docs/GPU.md) instead of the CPU"),
                   output_file("output",
                               "output image: .exr (float + metadata), .hdr, .pfm or .png "
                               "(tone-mapped preview)",
                               kImageFormats),
                   output_file("preview", "a tone-mapped PNG preview", kPngFormat, "no preview"),
                   output_file("false-colour", "a log-luminance false-colour PNG with legend",
                               kPngFormat, "none")}}),
      .relations = model_relations(),
      .model_parameters = true,
      .result = render_result().fields(),
      .result_type =
          "render::SkyImage (XYZ and linear sRGB images, the mask of pixels without a "
          "direction)"};
  op.relations.push_back(unread_without("false-colour-range", "false-colour"));
  op.check = [](Request& r) {
    const ImageOptions image = r.bind(image_schema(kRenderImage), kRenderImage.defaults());
    if (const auto unread = image.unread(r.values()); !unread.empty()) {
      std::string list;
      for (const auto& n : unread) list += (list.empty() ? "" : ", ") + spelled(n);
      r.warn(fmt::format("{} not used by {} {}; ignored", list, spelled("projection"),
                         to_string(image.projection)));
      for (const auto& n : unread) r.drop(n);
    }
    (void)image.camera();  // the layout's own checks (a cubemap's width) before any work
    if (r.given("gpu")) (void)gpu_backend("--gpu");
  };
  op.run = [](const Request& r, const ProgressSink&) { return run_render(r); };
  return op;
}

// ---- eval ---------------------------------------------------------------------------------------

struct EvalResult {
  std::string model{}, quantity{};
  std::vector<std::string> columns{};
  long long rows = 0;
  bool reference = false;
};

const ResultSchema<EvalResult>& eval_result() {
  using R = EvalResult;
  static const ResultSchema<R> s = [] {
    ResultSchema<R> s;
    s.text("model", "the sky model", &R::model)
        .text("quantity", "rgb, xyz, luminance or spectral", &R::quantity)
        .texts("columns", "the CSV's value columns (with --reference each one's _se after it)",
               &R::columns)
        .integer("rows", "1", "directions evaluated", &R::rows)
        .flag("reference", "the values are the model's reference integrator's", &R::reference);
    return s;
  }();
  return s;
}

Result run_eval(const Request& r) {
  EvaluationOptions options = r.bind(EvaluationOptions::schema());
  validate(options);
  options.sun = r.bind(SolarDisc::schema()).mode;
  const auto model = make_sky(r);
  warn_domain(r, *model, options.quantity == Quantity::spectral);
  validate(options, *model);
  const ReferenceOptions ref = r.bind(ReferenceOptions::schema());
  const ModelInfo& info = require_model(std::string(model->name()), "model");
  const std::string path = r.file("input").value_or("-");
  const std::string source = r.frontend().texts.count("input") ? "the " + spelled("input")
                             : path == "-"                     ? std::string("<stdin>")
                                                               : path;
  const std::string text = r.text_file("input");
  const auto rows = io::parse_directions_csv(text, source);
  EvalResult er{.model = std::string(model->name()),
                .quantity = std::get<std::string>(
                    EvaluationOptions::schema().values_of(options).all().at("quantity")),
                .columns = quantity_columns(options),
                .rows = static_cast<long long>(rows.size()),
                .reference = ref.reference};
  std::string out(io::kDirectionsHeader);
  for (const std::string& c : er.columns) out += "," + c;
  if (ref.reference)
    for (const std::string& c : quantity_columns(options)) out += "," + c + "_se";
  out += "\n";
  if (ref.reference) {
    const auto n = er.columns.size();
    for (std::size_t i = 0; i < n; ++i) er.columns.push_back(er.columns[i] + "_se");
  }
  for (const auto& row : rows) {
    out += row.text;
    const Vec3 view = direction_from_angles(row.zenith, row.azimuth);
    std::vector<double> values;
    if (ref.reference) {
      const ReferenceValue rv = evaluate_reference(info, *model, view, options, ref.request);
      values = rv.value;
      values.insert(values.end(), rv.standard_error.begin(), rv.standard_error.end());
    } else {
      values = evaluate(*model, view, options);
    }
    for (double v : values) {
      // No output may hold NaN or Inf: a value that overflows is an error naming the row.
      if (!std::isfinite(v))
        throw InvalidArgument(fmt::format(
            "{} line {}: model '{}' gives a non-finite value (overflow) in this direction", source,
            row.line, model->name()));
      out += fmt::format(",{}", v);
    }
    out += "\n";
  }
  // Written only once everything parsed: a bad row produces no partial output.
  Result res;
  r.write_text(res, "output", out);
  res.record = eval_result().record(er);
  return res;
}

OperationInfo eval_operation() {
  ParameterSpec input = input_file("input", "the directions: CSV zenith_deg,azimuth_deg [deg]");
  input.standard_stream = true;
  input.default_value = ParameterValue(std::string("-"));
  ParameterSpec output =
      output_file("output", "the values: CSV zenith_deg,azimuth_deg and the quantity's columns", {},
                  "standard output");
  output.standard_stream = true;
  output.default_value = ParameterValue(std::string("-"));
  OperationInfo op{
      .name = "eval",
      .summary = "evaluate a model for directions read as CSV (zenith_deg,azimuth_deg)",
      .description =
          "a sky model evaluated in given directions (zenith, azimuth): linear sRGB, "
          "XYZ, luminance or spectral radiance, of the sky, the solar disc or both",
      .parameters = concat({model_specs(),
                            EvaluationOptions::schema().specs(),
                            ReferenceOptions::schema().specs(),
                            {input, output}}),
      .relations = model_relations(),
      .model_parameters = true,
      .result = eval_result().fields(),
      .result_type =
          "one value per quantity column (models/evaluation.h, quantity_columns); with "
          "--reference a standard-error column after each"};
  for (const char* name : {"paths", "seed"})
    op.relations.push_back(unread_without(name, "reference"));
  op.check = [](Request& r) {
    EvaluationOptions options = r.bind(EvaluationOptions::schema());
    validate(options);
  };
  op.run = [](const Request& r, const ProgressSink&) { return run_eval(r); };
  return op;
}

}  // namespace

std::vector<OperationInfo> sky_operations() {
  return {render_operation(), eval_operation()};
}

}  // namespace skylight::operations::detail

namespace skylight::operations {

const OperationInfo& sky_declaration() {
  static const OperationInfo op{
      .name = "Sky",
      .summary = "a sky of one registered model",
      .description =
          "the model, the sun and the solar disc as render and eval take them, and the "
          "chosen model's own parameters",
      .parameters = model_specs(),
      .relations = detail::model_relations(),
      .model_parameters = true};
  return op;
}

}  // namespace skylight::operations
