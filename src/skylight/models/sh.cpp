#include "skylight/models/sh.h"

#include <fmt/format.h>

#include <array>
#include <string>
#include <vector>

#include "skylight/core/camera.h"
#include "skylight/core/data.h"
#include "skylight/core/parameters.h"
#include "skylight/io/file.h"
#include "skylight/models/preetham.h"
#include "skylight/sh/basis.h"
#include "skylight/sh/rotation.h"

namespace skylight {
namespace {

std::shared_ptr<const sh::PolynomialTable> shared_table(const std::string& path) {
  if (path.empty()) {
    // Parsed once: every `sh` model without --table shares it.
    static const auto embedded =
        std::make_shared<const sh::PolynomialTable>(load_sh_table(std::string()));
    return embedded;
  }
  return std::make_shared<const sh::PolynomialTable>(load_sh_table(path));
}

}  // namespace

sh::PolynomialTable load_sh_table(const std::string& path) {
  if (path.empty()) {
    return sh::table_from_json(std::string(data::embedded_file(kDefaultShTable)),
                               std::string("data/") + kDefaultShTable);
  }
  const std::vector<char> bytes = io::read_file(path);
  return sh::table_from_json(std::string(bytes.begin(), bytes.end()), path);
}

const ParameterSchema<ShParameters>& ShParameters::schema() {
  static const auto s = [] {
    ParameterSchema<ShParameters> s;
    s.text(&ShParameters::table,
           {.name = "table",
            .kind = ParameterKind::text,
            .default_value =
                Absent{std::string("the embedded Preetham table data/") + kDefaultShTable},
            .description = "SH polynomial table file (JSON from `skylight sh fit`)"});
    s.integer(&ShParameters::bands,
              {.name = "bands",
               .unit = "1",
               .kind = ParameterKind::integer,
               .min = 0,
               .max = sh::kMaxBands,
               .default_value = ParameterValue(0.0),
               .description = "SH bands N reconstructed (degrees 0..N-1); 0: all of the table's"});
    s.flag(&ShParameters::no_ringing_filter,
           {.name = "no-ringing-filter",
            .kind = ParameterKind::flag,
            .default_value = ParameterValue(false),
            .description = "reconstruct without the ringing filter (Habel 2008 eq. 5)"});
    s.optional_number(
        &ShParameters::turbidity,
        {.name = "turbidity",
         .unit = "1",
         .min = 0.0,
         .max = 1000.0,
         .default_value = Absent{"the middle of the table's range"},
         .description = "the table's second parameter (turbidity for preetham and hosek tables), "
                        "within the table's fitted range"});
    return s;
  }();
  return s;
}

ShSkyModel::ShSkyModel(const ShParameters& p) : ShSkyModel(p, shared_table(p.table)) {}

ShSkyModel::ShSkyModel(const ShParameters& p, std::shared_ptr<const sh::PolynomialTable> table)
    : SkyModel(p.sun), params_(p), table_(std::move(table)) {
  ShParameters::schema().validate(p, model_context(kName));
  SKYLIGHT_CHECK(table_ != nullptr, "ShSkyModel: no table");
  const sh::PolynomialTable& t = *table_;
  if (params_.bands == 0) params_.bands = t.bands;
  if (params_.bands > t.bands) {
    throw InvalidArgument(fmt::format("{}: {} {} exceeds the table's {}", model_context(kName),
                                      spelled("bands"), params_.bands, t.bands));
  }
  if (t.parameter.empty()) {
    if (params_.turbidity) {
      throw InvalidArgument(fmt::format("{}: {} given, but the table varies the sun zenith only",
                                        model_context(kName), spelled("turbidity")));
    }
  } else if (!params_.turbidity) {
    params_.turbidity = 0.5 * (t.tau_min + t.tau_max);
  }
  coefficients_ = sh::evaluate_table(t, p.sun.zenith, params_.turbidity.value_or(0.0),
                                     p.sun.azimuth, params_.bands, !params_.no_ringing_filter);
}

sh::Coefficients ShSkyModel::irradiance_coefficients() const {
  if (params_.no_ringing_filter) return sh::irradiance_coefficients(coefficients_);
  return sh::irradiance_coefficients(sh::evaluate_table(
      *table_, sun().zenith, params_.turbidity.value_or(0.0), sun().azimuth, params_.bands, false));
}

ParameterValues ShSkyModel::parameter_values() const {
  return ShParameters::schema().values_of(params_);
}

Xyz ShSkyModel::tristimulus(Vec3 view) const {
  const sh::Triple v = sh::reconstruct(coefficients_, view);
  if (table_->channels == sh::Channels::xyz) return {v[0], v[1], v[2]};
  return linear_srgb_to_xyz({v[0], v[1], v[2]});
}

Rgb ShSkyModel::rgb(Vec3 view) const {
  const sh::Triple v = sh::reconstruct(coefficients_, view);
  if (table_->channels == sh::Channels::linear_srgb) return {v[0], v[1], v[2]};
  return xyz_to_linear_srgb({v[0], v[1], v[2]});
}

Domain ShSkyModel::domain() const {
  return {};
}

const ParameterSchema<ShEvalOptions>& ShEvalOptions::schema() {
  static const ParameterSchema<ShEvalOptions> s = [] {
    ParameterSchema<ShEvalOptions> s;
    s.flag(&ShEvalOptions::irradiance,
           {.name = "irradiance",
            .kind = ParameterKind::flag,
            .description = "the irradiance coefficients A_l c_lm (clamped-cosine convolution)"});
    return s;
  }();
  return s;
}

const ParameterSchema<ShRenderOptions>& ShRenderOptions::schema() {
  static const ParameterSchema<ShRenderOptions> s = [] {
    ParameterSchema<ShRenderOptions> s;
    s.integer(&ShRenderOptions::width,
              {.name = "width",
               .unit = "px",
               .kind = ParameterKind::integer,
               .min = 2,
               .max = kMaxImageSide,
               .default_value = ParameterValue(static_cast<double>(ShRenderOptions{}.width)),
               .description = "env map width (height = width/2)"});
    return s;
  }();
  return s;
}

// The turbidities the embedded table was fitted over (its tau_min, tau_max).
constexpr std::array<double, 2> kEmbeddedTableTurbidity{2.5, 6.0};

ModelInfo ShSkyModel::registry_entry() {
  return ModelInfo{
      .name = std::string(kName),
      .description =
          "a sky reconstructed from an SH polynomial table (Habel, Mustata & Wimmer 2008: "
          "coefficients as polynomials in the sun zenith and turbidity, eq. 1; rotation to the "
          "sun's azimuth, eq. 4; ringing filter, eq. 5) fitted to any model by `skylight sh fit`",
      .output =
          "the table's channels (XYZ with Y [cd/m^2], or linear sRGB on the same scale) of the "
          "reconstruction sum c_lm Y_lm in every direction, below the horizon too, UNCLAMPED (it "
          "rings and may be negative); no solar disc",
      .parameters = ShParameters::schema().specs(),
      .domain =
          "the sun zenith and turbidity within the table's fitted ranges (refused outside); the "
          "error against the fitted model is in docs/SH.md",
      .make = model_factory<ShSkyModel, ShParameters>(),
      .unclamped = true,
      // T = 1..10 (a table of turbidity must cover them)
      .neural = NeuralPolicy::over_turbidity(1.0, 10.0),
      // The embedded table's turbidity over the range it was fitted on.
      .estimation = registry_estimation(
          std::string(kName),
          {{.parameter = "turbidity",
            .label = "turbidity",
            .min = kEmbeddedTableTurbidity[0],
            .max = kEmbeddedTableTurbidity[1],
            .grid_points = 8}},
          "the turbidity of the table (the embedded one: preetham's, fitted over T 2.5-6), free "
          "luminance scale"),
      // Habel 2008 §4: evaluating the table against projecting its model.
      .bench = BenchPolicy{.extra = BenchPolicy::Extra::sh_table},
      // The embedded table: preetham's XYZ, 7 bands, fitted over T 2.5-6 (its tau_min, tau_max;
      // checked by ReportPolicyMatchesTheEmbeddedData).
      .report = ReportPolicy{.title = "sh (Preetham table)",
                             .axis = "turbidity",
                             .axis_label = "T = ",
                             .colour = "#7f7f7f",
                             .axis_range = kEmbeddedTableTurbidity,
                             .source = std::string(PreethamModel::kName),
                             // the embedded table's 7 bands (its `bands`)
                             .truncation = "bands",
                             .truncation_range = {1, 7}},
      .no_gpu =
          "its reconstruction sums up to 49 SH basis functions whose coefficients are "
          "polynomials of the sun zenith and turbidity; that sum is not written as a shader "
          "yet",
  };
}

}  // namespace skylight
