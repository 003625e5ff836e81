// `skylight sh fit|eval|export|render|error`: SH polynomial tables (Habel, Mustata & Wimmer 2008;
// docs/SH.md) fitted to any registry model, evaluated, exported, rendered and measured. Each
// subcommand's flags are its operation's (operations/operations.h); the work is the library's
// (fit/sh_fit.h, models/sh.h, sh/).
#include <fmt/format.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "common.h"
#include "skylight/core/error.h"
#include "skylight/fit/sh_fit.h"
#include "skylight/io/file.h"
#include "skylight/io/image.h"
#include "skylight/models/sh.h"
#include "skylight/operations/operations.h"
#include "skylight/render/sky_render.h"
#include "skylight/render/tonemap.h"
#include "skylight/sh/basis.h"
#include "skylight/sh/irradiance.h"

namespace skylight::cli {
namespace {

std::string channel_names(sh::Channels c) {
  return c == sh::Channels::xyz ? "X,Y,Z" : "r,g,b";
}

// The flags of one sh subcommand, with its output and --json where it has them.
struct ShCommand {
  SchemaFlags flags;
  std::string output, sphere;
  bool json = false;

  // The sh model of the sun, table, bands, filter and tau given.
  std::unique_ptr<ShSkyModel> model(std::string_view context) const {
    const ParameterValues given = flags.values();
    ShParameters p;
    p.sun = sun_from_degrees(given.number("sun-zenith").value_or(kDefaultSunZenithDeg),
                             given.number("sun-azimuth").value_or(kDefaultSunAzimuthDeg));
    ShParameters::schema().bind(given.only(ShParameters::schema().specs()), p, context);
    return std::make_unique<ShSkyModel>(p);
  }
};

int run_fit(const ShCommand& c) {
  fit::ShFitSettings s =
      fit::sh_fit_settings(c.flags.bind(fit::ShFitRequest::schema(), {}, "sh fit"));
  Progress progress("sh fit");
  s.polynomial.progress = [&](int done, int total) {
    progress(done, total, fmt::format("projections of '{}'", s.model));
  };
  const sh::PolynomialTable t = fit::fit_sh_table(s);
  io::write_text_file(c.output, sh::table_to_json(t));
  std::cerr << fmt::format(
      "skylight sh fit: {} bands, degrees ({}, {}), {} coefficients in float = {} bytes, {:.1f} "
      "s\n",
      t.bands, t.degree_theta, t.degree_tau, t.coefficients.size(), t.bytes(),
      progress.elapsed_s());
  return kExitOk;
}

int run_eval(const ShCommand& c) {
  const auto model = c.model("sh eval");
  const bool irradiance = c.flags.bind(ShEvalOptions::schema(), {}, "sh eval").irradiance;
  const sh::Coefficients co = irradiance ? model->irradiance_coefficients() : model->coefficients();
  const std::string names = channel_names(model->table().channels);
  if (c.json) {
    const ParameterValues given = c.flags.values();
    nlohmann::json j;
    j["model"] = ShSkyModel::kName;
    j["fitted_model"] = model->table().model;
    j["channels"] = model->table().channels == sh::Channels::xyz ? "xyz" : "linear_srgb";
    j["quantity"] = irradiance ? "irradiance" : "radiance";
    j["bands"] = co.bands;
    // The irradiance convolves the unfiltered radiance (ShSkyModel::irradiance_coefficients).
    j["ringing_filter"] = !irradiance && !model->parameters().no_ringing_filter;
    j["sun_zenith_deg"] = given.number("sun-zenith").value_or(kDefaultSunZenithDeg);
    j["sun_azimuth_deg"] = given.number("sun-azimuth").value_or(kDefaultSunAzimuthDeg);
    if (model->parameters().turbidity) j["turbidity"] = *model->parameters().turbidity;
    j["index"] = "l (l + 1) + m";
    for (int ch = 0; ch < 3; ++ch) {
      std::vector<double> v;
      for (const auto& t : co.c) v.push_back(t[static_cast<std::size_t>(ch)]);
      j["coefficients"][names.substr(static_cast<std::size_t>(2 * ch), 1)] = v;
    }
    write_stdout(j.dump(1) + "\n");
    return kExitOk;
  }
  std::string out = "l,m," + names + "\n";
  for (int i = 0; i < sh::coefficient_count(co.bands); ++i) {
    const auto [l, m] = sh::degree_order(i);
    const auto& v = co.c[static_cast<std::size_t>(i)];
    out += fmt::format("{},{},{},{},{}\n", l, m, v[0], v[1], v[2]);
  }
  write_stdout(out);
  return kExitOk;
}

// Display images (.png) are clamped at 0; float files keep the unclamped reconstruction.
io::ImageF for_format(const std::string& path, io::ImageF img) {
  if (io::format_from_path(path) == io::ImageFormat::png)
    for (float& v : img.data) v = std::max(v, 0.0f);
  return img;
}

int run_render(const ShCommand& c) {
  (void)io::format_from_path(c.output);
  if (!c.sphere.empty()) (void)io::format_from_path(c.sphere);
  const auto model = c.model("sh render");
  const int width = c.flags.bind(ShRenderOptions::schema(), {}, "sh render").width;
  const auto sphere = c.flags.bind(sh::SphereOptions::schema(), {}, "sh render");
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
  render::write_image_or_preview(c.output, for_format(c.output, img.rgb), md);
  if (!c.sphere.empty()) {
    auto smd = md;
    smd.emplace_back("skylight:sphere_albedo", fmt::format("{}", sphere.albedo));
    render::write_image_or_preview(
        c.sphere,
        for_format(c.sphere, sh::diffuse_sphere(model->irradiance_coefficients(),
                                                model->table().channels, sphere)),
        smd);
  }
  return kExitOk;
}

// --table, or the embedded default.
sh::PolynomialTable table_of(const ShCommand& c) {
  const ParameterValues given = c.flags.values();
  const ParameterValue* path = given.find("table");
  return load_sh_table(path ? std::get<std::string>(*path) : std::string());
}

int run_export(const ShCommand& c) {
  const sh::PolynomialTable t = table_of(c);
  io::write_text_file(
      c.output, sh::export_table(t, c.flags.bind(sh::ExportOptions::schema(), {}, "sh export")));
  return kExitOk;
}

int run_error(const ShCommand& c) {
  const sh::PolynomialTable t = table_of(c);
  Progress progress("sh error");
  const fit::ShTableError e =
      fit::table_error(t, c.flags.bind(fit::ShErrorOptions::schema(), {}, "sh error"),
                       [&](int done, int total) { progress(done, total, "projections"); });
  const std::string names = channel_names(t.channels);
  nlohmann::json j = nlohmann::json::array();
  std::string text = fmt::format(
      "skylight sh error: model '{}', degrees ({}, {}), {} points, E in %\n{:>2} {:>3} {:>12} "
      "{:>12} {:>12} {:>12} {:>14}\n",
      t.model, t.degree_theta, t.degree_tau, e.points, "N", "ch", "E_mean worst", "E_mean median",
      "E_max worst", "E_max median", "worst at");
  for (const fit::ShErrorRow& r : e.rows) {
    const std::string name = names.substr(2 * static_cast<std::size_t>(r.channel), 1);
    const std::string where =
        t.parameter.empty()
            ? fmt::format("{:.2f} deg", rad_to_deg(r.worst_theta))
            : fmt::format("{:.2f} deg, {:.3g}", rad_to_deg(r.worst_theta), r.worst_tau);
    text += fmt::format("{:>2} {:>3} {:>12.5f} {:>12.5f} {:>12.5f} {:>12.5f} {:>14}\n", r.bands,
                        name, 100 * r.e_mean_worst, 100 * r.e_mean_median, 100 * r.e_max_worst,
                        100 * r.e_max_median, where);
    j.push_back({{"bands", r.bands},
                 {"channel", name},
                 {"e_mean_worst_percent", 100 * r.e_mean_worst},
                 {"e_mean_median_percent", 100 * r.e_mean_median},
                 {"e_max_worst_percent", 100 * r.e_max_worst},
                 {"e_max_median_percent", 100 * r.e_max_median},
                 {"worst_sun_zenith_deg", rad_to_deg(r.worst_theta)},
                 {"worst_tau", r.worst_tau}});
  }
  write_stdout(c.json ? j.dump(1) + "\n" : text);
  return kExitOk;
}

// One subcommand: its operation's flags, then the front end's own.
std::shared_ptr<ShCommand> subcommand(CLI::App& sh, Commands& commands, const char* name,
                                      const char* description, int (*run)(const ShCommand&),
                                      CLI::App** app) {
  auto c = std::make_shared<ShCommand>();
  *app = sh.add_subcommand(name, description);
  c->flags.add(**app, operations::find(std::string("sh ") + name).parameters);
  commands.push_back({*app, [c, run] { return run(*c); }});
  return c;
}

}  // namespace

void add_sh_command(CLI::App& app, Commands& commands) {
  auto* sh = app.add_subcommand(
      "sh",
      "spherical-harmonics sky lighting: fit, eval, export, render, error\n"
      "Spherical-harmonics sky lighting: polynomial tables of SH coefficients over the sun's "
      "zenith and turbidity (Habel et al. 2008; docs/SH.md).");
  sh->require_subcommand(1);
  CLI::App* cmd = nullptr;

  auto fit = subcommand(*sh, commands, "fit", "fit an SH polynomial table to a registry model",
                        run_fit, &cmd);
  fit->flags.option("model")->required();
  cmd->add_option("-o,--output", fit->output, "table file (JSON)")->required();

  auto eval =
      subcommand(*sh, commands, "eval",
                 "SH coefficients of the sky for a sun and turbidity\n"
                 "SH coefficients of the sky for a sun and turbidity: CSV l,m,channels, or JSON "
                 "(--json).",
                 run_eval, &cmd);
  cmd->add_flag("--json", eval->json, "JSON output");

  auto exp = subcommand(*sh, commands, "export", "write a table as a C header (or JSON)",
                        run_export, &cmd);
  cmd->add_option("-o,--output", exp->output, "output file")->required();

  auto ren =
      subcommand(*sh, commands, "render",
                 "the reconstructed sky as an env map; a diffuse sphere lit by it\n"
                 "The sky reconstructed from a table as an equirect environment map, and a diffuse "
                 "sphere lit by it (--sphere).",
                 run_render, &cmd);
  cmd->add_option("-o,--output", ren->output, "env map (.exr/.hdr/.pfm; .png clamped)")->required();
  cmd->add_option("--sphere", ren->sphere, "also a diffuse sphere lit by the SH sky here");

  auto err =
      subcommand(*sh, commands, "error",
                 "a table's reconstruction errors per band count\n"
                 "E_mean (Habel et al. 2008 eq. 3) and E_max (eq. 2) of a table per band count, "
                 "worst and median over the table's suns and turbidities.",
                 run_error, &cmd);
  cmd->add_flag("--json", err->json, "JSON output");
}

}  // namespace skylight::cli
