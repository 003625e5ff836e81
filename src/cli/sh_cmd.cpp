// `skylight sh fit|eval|export|render|error`: SH polynomial tables (Habel, Mustata & Wimmer 2008;
// docs/SH.md) fitted to any registry model, evaluated, exported, rendered and measured.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "common.h"
#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/core/statistics.h"
#include "skylight/fit/sh_fit.h"
#include "skylight/io/file.h"
#include "skylight/io/image.h"
#include "skylight/models/sh.h"
#include "skylight/render/sky_render.h"
#include "skylight/render/tonemap.h"
#include "skylight/sh/approximation_error.h"
#include "skylight/sh/basis.h"
#include "skylight/sh/irradiance.h"
#include "skylight/sh/rotation.h"

namespace skylight::cli {
namespace {

// Habel 2008 §2.2: the Preetham fit covers T in [2.5, 6].
constexpr double kPreethamTauMin = 2.5, kPreethamTauMax = 6.0;

const ParameterSpec& bands_spec() {
  static const ParameterSpec s{"bands",
                               "1",
                               ParameterKind::integer,
                               1,
                               sh::kMaxBands,
                               1,
                               ParameterValue(7.0),
                               "SH bands N (degrees l = 0..N-1, N^2 coefficients)"};
  return s;
}

// Hosek fits follow Hosek & Wilkie's structure by default (docs/SH.md, "Hosek fits", where the
// study that chose these is): one tau piece per turbidity interval of width 1 (the knots at the
// integers for an integer range, where Hosek interpolates linearly), degrees (17, 2) on 4
// turbidities per piece, in the sun zenith itself (elevation^(1/3) measured worse at equal degree).
constexpr int kHosekDegreeTheta = 17, kHosekDegreeTau = 2, kHosekGridTau = 4;
constexpr sh::ThetaAxis kHosekThetaAxis = sh::ThetaAxis::theta;

int integer_intervals(double lo, double hi) {
  return std::clamp(static_cast<int>(std::lround(hi - lo)), 1, sh::kMaxTauPieces);
}

std::string channel_names(sh::Channels c) {
  return c == sh::Channels::xyz ? "X,Y,Z" : "r,g,b";
}

// ---- fit ----------------------------------------------------------------------------------------

struct FitFlags {
  std::string model, parameter, channels = "xyz", output;
  int bands = 7;
  std::vector<double> degrees{17.0, 12.0}, range, theta_range_deg{0.0, 90.0}, grid;
  std::vector<std::string> set;
  double tolerance = sh::ProjectionOptions{}.tolerance;
  std::string theta_axis;               // empty: the model's default (kHosekThetaAxis)
  int tau_pieces = 0;                   // 0: the model's default
  std::optional<double> ground_albedo;  // absent: black lower hemisphere
  bool degrees_given = false;
};

int run_fit(const FitFlags& f) {
  const ModelInfo* info = find_model(f.model);
  if (!info) throw InvalidArgument(fmt::format("--model: unknown model '{}'", excerpt(f.model)));
  if (f.model == "sh") throw InvalidArgument("--model sh: a table cannot be fitted to a table");
  const auto spec_of = [&](const std::string& name) -> const ParameterSpec* {
    for (const auto& s : info->parameters)
      if (s.name == name) return &s;
    return nullptr;
  };
  fit::ShFitSettings s;
  s.model = info->name;
  // The varying parameter: from the model's schema; turbidity where the model has it.
  if (f.parameter.empty()) {
    s.polynomial.parameter = spec_of("turbidity") ? "turbidity" : "";
  } else {
    s.polynomial.parameter = f.parameter == "none" ? "" : f.parameter;
  }
  const ParameterSpec* tau =
      s.polynomial.parameter.empty() ? nullptr : spec_of(s.polynomial.parameter);
  if (!s.polynomial.parameter.empty() && (!tau || tau->kind != ParameterKind::number)) {
    throw InvalidArgument(fmt::format("--parameter: '{}' is not a number parameter of model '{}'",
                                      excerpt(s.polynomial.parameter), info->name));
  }
  for (const auto& kv : f.set) {
    const auto eq = kv.find('=');
    const ParameterSpec* spec = eq == std::string::npos ? nullptr : spec_of(kv.substr(0, eq));
    if (!spec) {
      throw InvalidArgument(
          fmt::format("--set {}: expected NAME=VALUE with NAME a parameter of model '{}'",
                      excerpt(kv), info->name));
    }
    const ParameterValue v = spec->parse(kv.substr(eq + 1));
    spec->check(v, model_context(info->name));
    s.fixed.set(spec->name, v);
  }
  s.polynomial.channels = f.channels == "xyz" ? sh::Channels::xyz : sh::Channels::linear_srgb;
  s.polynomial.bands = f.bands;
  s.polynomial.degree_theta = static_cast<int>(f.degrees[0]);
  s.polynomial.degree_tau = tau ? static_cast<int>(f.degrees[1]) : 0;
  if (!tau && f.degrees_given && f.degrees[1] != 0.0) {
    throw InvalidArgument("--degrees I,J: J must be 0 for a fit in the sun zenith only");
  }
  if (f.degrees[0] != std::floor(f.degrees[0]) || f.degrees[1] != std::floor(f.degrees[1]))
    throw InvalidArgument("--degrees I,J: whole numbers expected");
  s.polynomial.theta_min = deg_to_rad(f.theta_range_deg[0]);
  s.polynomial.theta_max = deg_to_rad(f.theta_range_deg[1]);
  if (!(f.theta_range_deg[0] < f.theta_range_deg[1]))
    throw InvalidArgument("--theta-range LO,HI: LO must be below HI");
  if (tau) {
    if (!f.range.empty()) {
      s.polynomial.tau_min = f.range[0];
      s.polynomial.tau_max = f.range[1];
    } else if (info->name == "preetham" && s.polynomial.parameter == "turbidity") {
      s.polynomial.tau_min = kPreethamTauMin;
      s.polynomial.tau_max = kPreethamTauMax;
    } else {
      s.polynomial.tau_min = tau->min;
      s.polynomial.tau_max = tau->max;
    }
    if (!(s.polynomial.tau_min < s.polynomial.tau_max))
      throw InvalidArgument("--range LO,HI: LO must be below HI");
    tau->check(s.polynomial.tau_min, "--range");
    tau->check(s.polynomial.tau_max, "--range");
  }
  if (!f.grid.empty()) {
    s.polynomial.grid_theta = static_cast<int>(f.grid[0]);
    s.polynomial.grid_tau = static_cast<int>(f.grid[1]);
  }
  const bool hosek_form = info->name == "hosek" && s.polynomial.parameter == "turbidity";
  s.polynomial.theta_axis =
      f.theta_axis == "elevation-cbrt" ? sh::ThetaAxis::elevation_cbrt : sh::ThetaAxis::theta;
  s.polynomial.tau_pieces = f.tau_pieces > 0 ? f.tau_pieces : 1;
  if (hosek_form && tau) {
    if (f.theta_axis.empty()) s.polynomial.theta_axis = kHosekThetaAxis;
    if (f.tau_pieces == 0)
      s.polynomial.tau_pieces = integer_intervals(s.polynomial.tau_min, s.polynomial.tau_max);
    if (!f.degrees_given) {
      s.polynomial.degree_theta = kHosekDegreeTheta;
      s.polynomial.degree_tau = kHosekDegreeTau;
    }
    if (f.grid.empty() && s.polynomial.tau_pieces > 1) s.polynomial.grid_tau = kHosekGridTau;
  }
  if (!tau && s.polynomial.tau_pieces != 1)
    throw InvalidArgument("--tau-pieces: a fit in the sun zenith only has one piece");
  s.projection.tolerance = f.tolerance;
  s.projection.ground_albedo = f.ground_albedo;
  Progress progress("sh fit");
  s.polynomial.progress = [&](int done, int total) {
    progress(done, total, fmt::format("projections of '{}'", info->name));
  };
  const sh::PolynomialTable t = fit::fit_sh_table(s);
  io::write_text_file(f.output, sh::table_to_json(t));
  std::cerr << fmt::format(
      "skylight sh fit: {} bands, degrees ({}, {}), {} coefficients in float = {} bytes, {:.1f} "
      "s\n",
      t.bands, t.degree_theta, t.degree_tau, t.coefficients.size(), t.bytes(),
      progress.elapsed_s());
  return kExitOk;
}

// ---- the reconstructed sky (eval, render)
// ---------------------------------------------------------

struct SkyFlags {
  std::string table;
  double sun_zenith_deg = kDefaultSunZenithDeg, sun_azimuth_deg = kDefaultSunAzimuthDeg;
  std::optional<double> turbidity;
  int bands = 0;
  bool no_filter = false;

  void add(CLI::App& cmd) {
    const auto& specs = ShParameters::schema();
    cmd.add_option("--table", table, specs.find("table")->help());
    const auto& sun = sun_parameter_specs();
    add_number(cmd, sun[0], sun_zenith_deg);
    add_number(cmd, sun[1], sun_azimuth_deg);
    add_number(cmd, *specs.find("turbidity"), turbidity);
    add_integer(cmd, *specs.find("bands"), bands);
    cmd.add_flag("--no-ringing-filter", no_filter, specs.find("no-ringing-filter")->help());
  }
  std::unique_ptr<ShSkyModel> make() const {
    ShParameters p;
    p.sun = sun_from_degrees(sun_zenith_deg, sun_azimuth_deg);
    p.table = table;
    p.bands = bands;
    p.no_ringing_filter = no_filter;
    p.turbidity = turbidity;
    return std::make_unique<ShSkyModel>(p);
  }
};

struct EvalFlags {
  SkyFlags sky;
  bool json = false, irradiance = false;
};

int run_eval(const EvalFlags& f) {
  const auto model = f.sky.make();
  const sh::Coefficients c =
      f.irradiance ? sh::irradiance_coefficients(model->coefficients()) : model->coefficients();
  const std::string names = channel_names(model->table().channels);
  if (f.json) {
    nlohmann::json j;
    j["model"] = "sh";
    j["fitted_model"] = model->table().model;
    j["channels"] = model->table().channels == sh::Channels::xyz ? "xyz" : "linear_srgb";
    j["quantity"] = f.irradiance ? "irradiance" : "radiance";
    j["bands"] = c.bands;
    j["ringing_filter"] = !f.sky.no_filter;
    j["sun_zenith_deg"] = f.sky.sun_zenith_deg;
    j["sun_azimuth_deg"] = f.sky.sun_azimuth_deg;
    if (model->parameters().turbidity) j["turbidity"] = *model->parameters().turbidity;
    j["index"] = "l (l + 1) + m";
    for (int ch = 0; ch < 3; ++ch) {
      std::vector<double> v;
      for (const auto& t : c.c) v.push_back(t[static_cast<std::size_t>(ch)]);
      j["coefficients"][names.substr(static_cast<std::size_t>(2 * ch), 1)] = v;
    }
    write_stdout(j.dump(1) + "\n");
    return kExitOk;
  }
  std::string out = "l,m," + names + "\n";
  for (int i = 0; i < sh::coefficient_count(c.bands); ++i) {
    const auto [l, m] = sh::degree_order(i);
    const auto& v = c.c[static_cast<std::size_t>(i)];
    out += fmt::format("{},{},{},{},{}\n", l, m, v[0], v[1], v[2]);
  }
  write_stdout(out);
  return kExitOk;
}

struct RenderFlags {
  SkyFlags sky;
  std::string output, sphere;
  int width = 512, sphere_size = 256;
  double albedo = 0.8;
};

// A diffuse sphere of albedo rho seen from the south (the view looks north, east to the right):
// L = rho / pi * E(n), E the clamped-cosine convolution of the sky (Ramamoorthi & Hanrahan 2001).
io::ImageF diffuse_sphere(const ShSkyModel& model, int size, double albedo) {
  const sh::Coefficients e = sh::irradiance_coefficients(model.coefficients());
  io::ImageF img(size, size, 3);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const double u = (2.0 * (x + 0.5) / size) - 1.0, v = 1.0 - (2.0 * (y + 0.5) / size);
      const double r2 = u * u + v * v;
      if (r2 > 1.0) continue;
      const sh::Triple t = sh::reconstruct(e, Vec3{u, -std::sqrt(1.0 - r2), v});
      const Xyz xyz = model.table().channels == sh::Channels::xyz
                          ? Xyz{t[0], t[1], t[2]}
                          : linear_srgb_to_xyz({t[0], t[1], t[2]});
      const Rgb rgb = xyz_to_linear_srgb(xyz);
      float* p = img.pixel(x, y);
      p[0] = static_cast<float>(albedo / kPi * rgb.r);
      p[1] = static_cast<float>(albedo / kPi * rgb.g);
      p[2] = static_cast<float>(albedo / kPi * rgb.b);
    }
  }
  return img;
}

// Display images (.png) are clamped at 0; float files keep the unclamped reconstruction.
io::ImageF for_format(const std::string& path, io::ImageF img) {
  if (io::format_from_path(path) == io::ImageFormat::png)
    for (float& v : img.data) v = std::max(v, 0.0f);
  return img;
}

int run_render(const RenderFlags& f) {
  (void)io::format_from_path(f.output);
  if (!f.sphere.empty()) (void)io::format_from_path(f.sphere);
  const auto model = f.sky.make();
  render::RenderSettings s;
  s.projection = Projection::equirect;
  s.width = f.width;
  s.height = f.width / 2;
  validate(s);
  const render::SkyImage img = render::render_sky(*model, s);
  auto md = model_metadata(*model, "sky");
  md.emplace_back("skylight:projection", "equirect");
  md.emplace_back("skylight:pixel_unit",
                  "linear sRGB (D65), Y = luminance [cd/m^2]; SH reconstruction, unclamped in "
                  "float files, clamped at 0 in PNG");
  render::write_image_or_preview(f.output, for_format(f.output, img.rgb), md);
  if (!f.sphere.empty()) {
    auto smd = md;
    smd.emplace_back("skylight:sphere_albedo", fmt::format("{}", f.albedo));
    render::write_image_or_preview(
        f.sphere, for_format(f.sphere, diffuse_sphere(*model, f.sphere_size, f.albedo)), smd);
  }
  return kExitOk;
}

// ---- export -------------------------------------------------------------------------------------

struct ExportFlags {
  std::string table, output, name = "skylight_sh_table";
  bool c_header = false, monomial = false;
};

int run_export(const ExportFlags& f) {
  const sh::PolynomialTable t = load_sh_table(f.table);
  io::write_text_file(
      f.output, f.c_header ? sh::table_to_c_header(t, f.name, f.monomial) : sh::table_to_json(t));
  return kExitOk;
}

// ---- error --------------------------------------------------------------------------------------

struct ErrorFlags {
  std::string table;
  std::vector<double> points{10.0, 7.0};
  bool json = false;
};

// Habel 2008 §3.2, Fig. 3: E_max (eq. 2) and E_mean (eq. 3) of the table against converged
// projections of its model, at the cell midpoints of a (theta, tau) grid over the fitted range,
// per band count N and channel; worst and median over the points.
int run_error(const ErrorFlags& f) {
  const sh::PolynomialTable t = load_sh_table(f.table);
  const int nt = static_cast<int>(f.points[0]);
  const int nv = t.parameter.empty() ? 1 : static_cast<int>(f.points[1]);
  const int n_bands = t.bands;
  // [band N - 1][channel] -> values over the points
  std::vector<std::array<std::vector<double>, 3>> e_mean(static_cast<std::size_t>(n_bands)),
      e_max(static_cast<std::size_t>(n_bands));
  Progress progress("sh error");
  for (int it = 0; it < nt; ++it) {
    for (int iv = 0; iv < nv; ++iv) {
      const double theta = t.theta_min + (t.theta_max - t.theta_min) * (it + 0.5) / nt;
      const double tau = t.tau_min + (t.tau_max - t.tau_min) * (iv + 0.5) / nv;
      const sh::Projection ref = fit::project_reference(t, theta, tau, 0.0, n_bands);
      const sh::Coefficients rec = sh::evaluate_table(t, theta, tau, 0.0, n_bands, false);
      SkyParameters sp;
      sp.sun = {theta, 0.0};
      sp.values = t.fixed;
      if (!t.parameter.empty()) sp.values.set(t.parameter, tau);
      const auto model = make_sky_model(t.model, sp);
      const sh::Triple l_min = fit::minimum_over_sky(*model, t.channels);
      for (int n = 1; n <= n_bands; ++n) {
        const sh::ErrorMeasures m = sh::error_measures(ref.coefficients, rec, n, l_min);
        for (std::size_t ch = 0; ch < 3; ++ch) {
          e_mean[static_cast<std::size_t>(n - 1)][ch].push_back(m.e_mean[ch]);
          e_max[static_cast<std::size_t>(n - 1)][ch].push_back(m.e_max[ch]);
        }
      }
      progress(it * nv + iv + 1, nt * nv, "projections");
    }
  }
  const std::string names = channel_names(t.channels);
  nlohmann::json j = nlohmann::json::array();
  std::string text = fmt::format(
      "skylight sh error: model '{}', degrees ({}, {}), {} points, E in %\n{:>2} {:>3} {:>12} "
      "{:>12} {:>12} {:>12}\n",
      t.model, t.degree_theta, t.degree_tau, nt * nv, "N", "ch", "E_mean worst", "E_mean median",
      "E_max worst", "E_max median");
  for (int n = 1; n <= n_bands; ++n) {
    for (std::size_t ch = 0; ch < 3; ++ch) {
      const auto& a = e_mean[static_cast<std::size_t>(n - 1)][ch];
      const auto& b = e_max[static_cast<std::size_t>(n - 1)][ch];
      const double wm = *std::max_element(a.begin(), a.end()), mm = median(a);
      const double wx = *std::max_element(b.begin(), b.end()), mx = median(b);
      const std::string name = names.substr(2 * ch, 1);
      text += fmt::format("{:>2} {:>3} {:>12.5f} {:>12.5f} {:>12.5f} {:>12.5f}\n", n, name,
                          100 * wm, 100 * mm, 100 * wx, 100 * mx);
      j.push_back({{"bands", n},
                   {"channel", name},
                   {"e_mean_worst_percent", 100 * wm},
                   {"e_mean_median_percent", 100 * mm},
                   {"e_max_worst_percent", 100 * wx},
                   {"e_max_median_percent", 100 * mx}});
    }
  }
  write_stdout(f.json ? j.dump(1) + "\n" : text);
  return kExitOk;
}

}  // namespace

void add_sh_command(CLI::App& app, Commands& commands) {
  auto* sh = app.add_subcommand(
      "sh", "spherical-harmonics sky lighting: polynomial SH tables (Habel et al. 2008)");
  sh->require_subcommand(1);

  auto ff = std::make_shared<FitFlags>();
  auto* fit = sh->add_subcommand("fit", "fit an SH polynomial table to a registry model");
  fit->add_option("--model", ff->model, "the model fitted (any of `skylight models` but sh)")
      ->required();
  add_integer(*fit, bands_spec(), ff->bands);
  auto* degrees =
      add_numbers(*fit,
                  {"degrees", "1", ParameterKind::numbers, 0, 40, 2, ParameterValue(ff->degrees),
                   "polynomial degrees I,J in the sun zenith and the second parameter (J = 0 for a "
                   "zenith-only fit)"},
                  ff->degrees);
  fit->add_option("--parameter", ff->parameter,
                  "the varying parameter tau (a number of the model's schema); default turbidity "
                  "where the model has one, else none; 'none': the sun zenith only");
  add_numbers(*fit,
              {"range", "1", ParameterKind::numbers, -1e9, 1e9, 2,
               Absent{"preetham: 2.5,6 "
                      "(Habel 2008); others: the parameter's whole range"},
               "range LO,HI of tau"},
              ff->range);
  add_numbers(*fit,
              {"theta-range", "deg", ParameterKind::numbers, 0, 90, 2,
               ParameterValue(ff->theta_range_deg), "range LO,HI of the sun zenith"},
              ff->theta_range_deg);
  add_numbers(*fit,
              {"grid", "1", ParameterKind::numbers, 1, 1000, 2,
               Absent{"2 (degree + 1) + 1 points each"}, "fitting grid points in theta, tau"},
              ff->grid);
  fit->add_option("--set", ff->set,
                  "NAME=VALUE: a model parameter held fixed (e.g. albedo=0.3, cie-type=7); "
                  "repeatable");
  fit->add_option("--channels", ff->channels, "xyz (default) or linear-srgb")
      ->check(CLI::IsMember({"xyz", "linear-srgb"}));
  add_number(*fit,
             {"tolerance", "1", ParameterKind::number, 1e-9, 1e-1, 1, ParameterValue(ff->tolerance),
              "projection convergence: largest coefficient change relative to c_00"},
             ff->tolerance);
  fit->add_option("--theta-axis", ff->theta_axis,
                  "the sun-zenith coordinate of the fit: theta (default), or elevation-cbrt "
                  "((elevation / 90 deg)^(1/3), Hosek's)")
      ->check(CLI::IsMember({"theta", "elevation-cbrt"}));
  add_integer(*fit,
              {"tau-pieces", "1", ParameterKind::integer, 1, sh::kMaxTauPieces, 1,
               Absent{"hosek: one per unit of turbidity (degrees 17,2, 4 turbidities each); "
                      "others: 1"},
               "equal pieces of the tau range, each its own polynomial in tau"},
              ff->tau_pieces);
  add_number(
      *fit,
      {"ground-albedo", "1", ParameterKind::number, 0, 1, 1, Absent{"the lower hemisphere black"},
       "the lower hemisphere as a uniform ground of this albedo lit by the sky and the sun "
       "(L = albedo E / pi)"},
      ff->ground_albedo);
  fit->add_option("-o,--output", ff->output, "table file (JSON)")->required();
  commands.push_back({fit, [ff, degrees] {
                        ff->degrees_given = degrees->count() > 0;
                        return run_fit(*ff);
                      }});

  auto ef = std::make_shared<EvalFlags>();
  auto* eval = sh->add_subcommand(
      "eval", "SH coefficients of the sky for a sun and turbidity (CSV l,m,channels or --json)");
  ef->sky.add(*eval);
  eval->add_flag("--irradiance", ef->irradiance,
                 "the irradiance coefficients A_l c_lm (clamped-cosine convolution)");
  eval->add_flag("--json", ef->json, "JSON output");
  commands.push_back({eval, [ef] { return run_eval(*ef); }});

  auto xf = std::make_shared<ExportFlags>();
  auto* exp = sh->add_subcommand("export", "write a table as a C header (or JSON)");
  exp->add_option("--table", xf->table, ShParameters::schema().find("table")->help());
  exp->add_flag("--c-header", xf->c_header, "a C header (default: JSON)");
  exp->add_flag("--monomial", xf->monomial,
                "with --c-header: also the published monomial form p_ij theta^i tau^j in double");
  exp->add_option("--name", xf->name, "C identifier of the arrays; default skylight_sh_table");
  exp->add_option("-o,--output", xf->output, "output file")->required();
  commands.push_back({exp, [xf] {
                        if (xf->monomial && !xf->c_header)
                          throw InvalidArgument("--monomial needs --c-header");
                        return run_export(*xf);
                      }});

  auto rf = std::make_shared<RenderFlags>();
  auto* ren = sh->add_subcommand(
      "render", "the reconstructed sky as an equirect env map, and a diffuse sphere lit by it");
  rf->sky.add(*ren);
  add_integer(*ren,
              {"width", "px", ParameterKind::integer, 2, kMaxImageSide, 1,
               ParameterValue(static_cast<double>(rf->width)), "env map width (height = width/2)"},
              rf->width);
  ren->add_option("-o,--output", rf->output, "env map (.exr/.hdr/.pfm; .png clamped)")->required();
  ren->add_option("--sphere", rf->sphere, "also a diffuse sphere lit by the SH sky here");
  add_integer(*ren,
              {"sphere-size", "px", ParameterKind::integer, 2, 8192, 1,
               ParameterValue(static_cast<double>(rf->sphere_size)), "sphere image side"},
              rf->sphere_size);
  add_number(*ren,
             {"sphere-albedo", "1", ParameterKind::number, 0, 1, 1, ParameterValue(rf->albedo),
              "diffuse albedo of the sphere"},
             rf->albedo);
  commands.push_back({ren, [rf] { return run_render(*rf); }});

  auto rrf = std::make_shared<ErrorFlags>();
  auto* err = sh->add_subcommand(
      "error", "E_mean (eq. 3) and E_max (eq. 2) of a table per band count, worst and median");
  err->add_option("--table", rrf->table, ShParameters::schema().find("table")->help());
  add_numbers(*err,
              {"points", "1", ParameterKind::numbers, 1, 1000, 2, ParameterValue(rrf->points),
               "test points (cell midpoints) in theta, tau"},
              rrf->points);
  err->add_flag("--json", rrf->json, "JSON output");
  commands.push_back({err, [rrf] { return run_error(*rrf); }});
}

}  // namespace skylight::cli
