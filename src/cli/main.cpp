// skylight command-line tool: a thin front end (STYLE.md §9). Each subcommand parses and validates
// its flags (degrees here only), converts to the library's radians, calls the library and writes
// outputs that record every parameter and the version.
//
// Exit status: 0 success, 2 usage error or invalid value, 1 runtime failure (I/O etc.).
#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "skylight/analysis/scan.h"
#include "skylight/core/error.h"
#include "skylight/core/parallel.h"
#include "skylight/io/file.h"
#include "skylight/io/image.h"
#include "skylight/models/sky_model.h"
#include "skylight/render/false_colour.h"
#include "skylight/render/sky_render.h"
#include "skylight/render/tonemap.h"
#include "skylight/report/report.h"
#include "skylight/version.h"

namespace sl = skylight;

namespace {

constexpr int kExitOk = 0;
constexpr int kExitRuntime = 1;
constexpr int kExitUsage = 2;

// A range check that also rejects NaN and infinities (CLI11's Range lets NaN through).
CLI::Validator finite_range(double min, double max, const std::string& unit) {
  return CLI::Validator(
      [min, max](std::string& s) -> std::string {
        double v = 0.0;
        try {
          std::size_t used = 0;
          v = std::stod(s, &used);
          if (used != s.size()) return fmt::format("'{}' is not a number", s);
        } catch (const std::exception&) {
          return fmt::format("'{}' is not a number", s);
        }
        if (!std::isfinite(v)) return fmt::format("{} is not a finite number", s);
        if (v < min || v > max) return fmt::format("{} is outside [{}, {}]", s, min, max);
        return {};
      },
      fmt::format("{} in [{}, {}]", unit, min, max));
}

// Model flags shared by render and eval (bench times each model at its default parameters).
struct ModelFlags {
  std::string model;
  std::optional<double> sun_zenith_deg, sun_elevation_deg;
  double sun_azimuth_deg = 180.0;
  double turbidity = 3.0;
  std::optional<double> albedo;  // default 0.3; nishita: no ground reflection unless given
  int cie_type = 12;
  // nishita (physically based): observer, sun irradiance, planet and atmosphere overrides.
  double observer_altitude_m = 0.0;
  std::optional<double> solar_irradiance, ground_radius_m, top_radius_m, rayleigh_scale_height_m,
      mie_scale_height_m, mie_g, ozone_du;
  std::optional<double> zenith_luminance;
  std::vector<double> perez;
  bool include_sun = false, sun_only = false;

  void add(CLI::App& app, bool model_required) {
    std::string names;
    for (const auto& m : sl::model_registry()) names += (names.empty() ? "" : "|") + m.name;
    auto* opt =
        app.add_option("--model", model, "sky model: " + names + " (see `skylight models`)");
    if (model_required) opt->required();
    auto* z = app.add_option("--sun-zenith", sun_zenith_deg,
                             "solar zenith angle [deg], 0-180 (>90: below the horizon); default 45")
                  ->check(finite_range(0, 180, "deg"));
    auto* e = app.add_option("--sun-elevation", sun_elevation_deg,
                             "solar elevation [deg], -90-90 (alternative to --sun-zenith)")
                  ->check(finite_range(-90, 90, "deg"));
    z->excludes(e);
    app.add_option("--sun-azimuth", sun_azimuth_deg,
                   "solar azimuth [deg] from north towards east, -360-360; default 180 (south)")
        ->check(finite_range(-360, 360, "deg"));
    app.add_option("--turbidity", turbidity, "atmospheric turbidity T [1], 1-64; default 3")
        ->check(finite_range(1, 64, "1"));
    app.add_option("--albedo", albedo,
                   "ground albedo [1], 0-1; default 0.3 (unused by perez, "
                   "preetham, cie; nishita: no ground reflection unless given)")
        ->check(finite_range(0, 1, "1"));
    app.add_option("--observer-altitude", observer_altitude_m,
                   "observer altitude above the ground [m], 0-1e7; default 0 (nishita)")
        ->check(finite_range(0, 1e7, "m"));
    app.add_option("--solar-irradiance", solar_irradiance,
                   "flat extraterrestrial solar irradiance [W m^-2 nm^-1], 1e-30-1e30; 1 = "
                   "radiance per unit irradiance; default: ASTM G-173 spectrum (nishita)")
        ->check(finite_range(1e-30, 1e30, "W m^-2 nm^-1"));
    app.add_option("--ground-radius", ground_radius_m,
                   "planet radius [m], 1-1e9; default 6360e3 (nishita)")
        ->check(finite_range(1, 1e9, "m"));
    app.add_option("--top-radius", top_radius_m,
                   "radius of the top of the atmosphere [m], 1-1e9, > ground radius; default "
                   "6420e3, or ground radius + 60 km with --ground-radius (nishita)")
        ->check(finite_range(1, 1e9, "m"));
    app.add_option("--rayleigh-scale-height", rayleigh_scale_height_m,
                   "Rayleigh scale height [m], 1-1e7; default 8000 (nishita)")
        ->check(finite_range(1, 1e7, "m"));
    app.add_option("--mie-scale-height", mie_scale_height_m,
                   "Mie scale height [m], 1-1e7; default 1200 (nishita)")
        ->check(finite_range(1, 1e7, "m"));
    app.add_option("--mie-g", mie_g,
                   "Mie Cornette-Shanks asymmetry g [1], -0.999-0.999; default "
                   "0.8 (nishita)")
        ->check(finite_range(-0.999, 0.999, "1"));
    app.add_option("--ozone", ozone_du,
                   "add an ozone layer (absorption only; tent 10-40 km peaking at 25 km) holding "
                   "this column [Dobson units], 0-1000; Earth ~300; default: none (nishita)")
        ->check(finite_range(0, 1000, "DU"));
    app.add_option("--cie-type", cie_type,
                   "CIE sky type 1-15, 16 = traditional overcast; default 12")
        ->check(CLI::Range(1, 16));
    app.add_option("--zenith-luminance", zenith_luminance,
                   "zenith luminance [cd/m^2], 1e-9-1e9; required by perez; cie default: "
                   "Kittler-Darula typical")
        ->check(finite_range(1e-9, 1e9, "cd/m^2"));
    app.add_option("--perez", perez, "Perez coefficients A,B,C,D,E [1], each -50-50 (model perez)")
        ->delimiter(',')
        ->expected(5)
        ->check(finite_range(-50, 50, "1"));
    auto* inc =
        app.add_flag("--include-sun", include_sun, "add the solar disc (models with a sun)");
    auto* only = app.add_flag("--sun-only", sun_only, "the solar disc alone, without the sky");
    inc->excludes(only);
  }

  sl::SkyParameters parameters() const {
    sl::SkyParameters p;
    const double zenith_deg = sun_zenith_deg      ? *sun_zenith_deg
                              : sun_elevation_deg ? 90.0 - *sun_elevation_deg
                                                  : 45.0;
    p.sun.zenith = sl::deg_to_rad(zenith_deg);
    p.sun.azimuth = sl::wrap_azimuth(sl::deg_to_rad(sun_azimuth_deg));
    p.turbidity = turbidity;
    p.ground_albedo = albedo.value_or(0.3);
    p.cie_type = cie_type;
    p.observer_altitude_m = observer_altitude_m;
    p.solar_irradiance = solar_irradiance;
    if (albedo || ground_radius_m || top_radius_m || rayleigh_scale_height_m ||
        mie_scale_height_m || mie_g || ozone_du) {
      sl::atmosphere::AtmosphereParameters a;
      if (ground_radius_m) {
        a.ground_radius_m = *ground_radius_m;
        a.top_radius_m = *ground_radius_m +
                         (sl::atmosphere::kEarthTopRadius - sl::atmosphere::kEarthGroundRadius);
      }
      if (top_radius_m) a.top_radius_m = *top_radius_m;
      if (!(a.top_radius_m > a.ground_radius_m))
        throw sl::InvalidArgument(fmt::format("--top-radius {} must exceed --ground-radius {}",
                                              a.top_radius_m, a.ground_radius_m));
      if (rayleigh_scale_height_m) a.components[0].scale_height_m = *rayleigh_scale_height_m;
      if (mie_scale_height_m) a.components[1].scale_height_m = *mie_scale_height_m;
      if (mie_g) a.components[1].g = *mie_g;
      if (ozone_du) a.components.push_back(sl::atmosphere::earth_ozone(*ozone_du));
      a.ground_albedo = albedo;
      p.atmosphere = a;
    }
    p.zenith_luminance = zenith_luminance;
    if (!perez.empty()) {
      if (perez.size() != 5)
        throw sl::InvalidArgument(
            fmt::format("--perez needs 5 values A,B,C,D,E, got {}", perez.size()));
      p.perez_coefficients =
          std::array<double, 5>{perez[0], perez[1], perez[2], perez[3], perez[4]};
    }
    return p;
  }

  std::unique_ptr<sl::SkyModel> make() const {
    auto m = sl::make_sky_model(model, parameters());
    if ((include_sun || sun_only) && !m->has_sun())
      throw sl::InvalidArgument(
          fmt::format("--include-sun/--sun-only: model '{}' has no sun", model));
    return m;
  }

  sl::io::Metadata metadata() const {
    const auto p = parameters();
    sl::io::Metadata md{
        {"skylight:version", sl::kVersion},
        {"skylight:model", model},
        {"skylight:sun_zenith_deg", fmt::format("{}", sl::rad_to_deg(p.sun.zenith))},
        {"skylight:sun_azimuth_deg", fmt::format("{}", sl::rad_to_deg(p.sun.azimuth))},
        {"skylight:turbidity", fmt::format("{}", turbidity)},
        {"skylight:albedo", model == "nishita" && !albedo
                                ? std::string("none")
                                : fmt::format("{}", albedo.value_or(0.3))},
        {"skylight:observer_altitude_m", fmt::format("{}", observer_altitude_m)},
        {"skylight:cie_type", fmt::format("{}", cie_type)},
        {"skylight:sun", sun_only      ? "sun-only"
                         : include_sun ? "sky+sun"
                                       : "sky"}};
    if (solar_irradiance)
      md.emplace_back("skylight:solar_irradiance_W_m2_nm", fmt::format("{}", *solar_irradiance));
    if (p.atmosphere)
      md.emplace_back(
          "skylight:atmosphere",
          fmt::format(
              "ground_radius_m={} top_radius_m={} rayleigh_H_m={} mie_H_m={} mie_g={} ozone_DU={}",
              p.atmosphere->ground_radius_m, p.atmosphere->top_radius_m,
              p.atmosphere->components[0].scale_height_m,
              p.atmosphere->components[1].scale_height_m, p.atmosphere->components[1].g,
              ozone_du.value_or(0.0)));
    if (zenith_luminance)
      md.emplace_back("skylight:zenith_luminance_cd_m2", fmt::format("{}", *zenith_luminance));
    if (!perez.empty())
      md.emplace_back("skylight:perez", fmt::format("{},{},{},{},{}", perez[0], perez[1], perez[2],
                                                    perez[3], perez[4]));
    return md;
  }
};

// Warns (stderr, one line each) where the model is outside its valid domain.
void report_domain(const sl::SkyModel& m) {
  for (const auto& issue : m.domain().issues)
    std::cerr << fmt::format("skylight: warning: {} ({}): {}\n", m.name(),
                             sl::to_string(issue.validity), issue.message);
}

// ---- models -------------------------------------------------------------------------------------
int run_models(bool json) {
  if (json) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& m : sl::model_registry()) {
      nlohmann::json params = nlohmann::json::array();
      for (const auto& p : m.parameters)
        params.push_back({{"name", p.name},
                          {"unit", p.unit},
                          {"min", p.min},
                          {"max", p.max},
                          {"default", p.default_value},
                          {"description", p.description}});
      out.push_back({{"name", m.name},
                     {"description", m.description},
                     {"output", m.output},
                     {"parameters", params},
                     {"domain", m.domain},
                     {"spectral", m.spectral},
                     {"sun", m.sun}});
    }
    std::cout << out.dump(2) << "\n";
    return kExitOk;
  }
  for (const auto& m : sl::model_registry()) {
    std::cout << fmt::format("{}\n  {}\n  output: {}\n  domain: {}\n  parameters:\n", m.name,
                             m.description, m.output, m.domain);
    for (const auto& p : m.parameters)
      std::cout << fmt::format("    --{:<18} [{}] {} .. {}, default {}: {}\n", p.name, p.unit,
                               p.min, p.max, p.default_value, p.description);
  }
  return kExitOk;
}

// ---- render -------------------------------------------------------------------------------------
struct RenderFlags {
  std::string projection = "equirect";
  std::string lens = "equidistant";
  std::optional<double> fov_deg;  // fisheye default 180, camera default 60
  double north_angle_deg = 0.0;
  double look_elevation_deg = 0.0, look_azimuth_deg = 0.0;
  int width = 1024, height = 512;
  std::string output, preview, false_colour;
  std::vector<double> fc_range{0.0, 6.0};
};

int run_render(const ModelFlags& mf, const RenderFlags& rf) {
  namespace r = sl::render;
  r::RenderSettings s;
  s.projection = *r::parse_projection(rf.projection);
  s.width = rf.width;
  s.height = rf.height;
  s.fisheye.lens = *sl::parse_fisheye_lens(rf.lens);
  s.fisheye.fov = sl::deg_to_rad(rf.fov_deg.value_or(180.0));
  s.fisheye.north_angle = sl::deg_to_rad(rf.north_angle_deg);
  s.camera.look_zenith = sl::deg_to_rad(90.0 - rf.look_elevation_deg);
  s.camera.look_azimuth = sl::wrap_azimuth(sl::deg_to_rad(rf.look_azimuth_deg));
  s.camera.vertical_fov = sl::deg_to_rad(rf.fov_deg.value_or(60.0));
  s.sun = mf.sun_only      ? r::SunMode::sun_only
          : mf.include_sun ? r::SunMode::sky_and_sun
                           : r::SunMode::sky;
  r::validate(s);
  (void)sl::io::format_from_path(rf.output);
  if (!rf.preview.empty() && sl::io::format_from_path(rf.preview) != sl::io::ImageFormat::png)
    throw sl::InvalidArgument(fmt::format("--preview '{}' must be a .png file", rf.preview));
  if (!rf.false_colour.empty() &&
      sl::io::format_from_path(rf.false_colour) != sl::io::ImageFormat::png)
    throw sl::InvalidArgument(
        fmt::format("--false-colour '{}' must be a .png file", rf.false_colour));
  if (!(rf.fc_range[0] < rf.fc_range[1]))
    throw sl::InvalidArgument(fmt::format("--false-colour-range {},{}: LO must be below HI",
                                          rf.fc_range[0], rf.fc_range[1]));
  const auto model = mf.make();
  report_domain(*model);
  const r::SkyImage img = r::render_sky(*model, s);

  auto md = mf.metadata();
  md.emplace_back("skylight:projection", rf.projection);
  if (s.projection == r::Projection::camera) {
    md.emplace_back("skylight:fov_deg", fmt::format("{}", rf.fov_deg.value_or(60.0)));
    md.emplace_back("skylight:look_elevation_deg", fmt::format("{}", rf.look_elevation_deg));
    md.emplace_back("skylight:look_azimuth_deg", fmt::format("{}", rf.look_azimuth_deg));
  }
  if (s.projection == r::Projection::fisheye) {
    md.emplace_back("skylight:lens", rf.lens);
    md.emplace_back("skylight:fov_deg", fmt::format("{}", rf.fov_deg.value_or(180.0)));
    md.emplace_back("skylight:north_angle_deg", fmt::format("{}", rf.north_angle_deg));
  }
  md.emplace_back("skylight:pixel_unit", "linear sRGB (D65), Y = luminance [cd/m^2]");
  // What the model actually used: its zenith luminance and where it stands in its domain.
  md.emplace_back("skylight:zenith_luminance_evaluated_cd_m2",
                  fmt::format("{}", model->tristimulus({0.0, 0.0, 1.0}).Y));
  md.emplace_back("skylight:domain", std::string(sl::to_string(model->domain().worst())));
  r::write_image_or_preview(rf.output, img.rgb, md);
  if (!rf.preview.empty()) r::write_image_or_preview(rf.preview, img.rgb, md);
  if (!rf.false_colour.empty()) {
    sl::io::ImageF lum(img.xyz.width, img.xyz.height, 1);
    for (std::size_t i = 0; i < lum.data.size(); ++i) lum.data[i] = img.xyz.data[3 * i + 1];
    r::FalseColourOptions fo;
    fo.log10_min = rf.fc_range[0];
    fo.log10_max = rf.fc_range[1];
    sl::io::write_png(rf.false_colour, r::false_colour(lum, fo, &img.mask), md);
  }
  return kExitOk;
}

// ---- eval ---------------------------------------------------------------------------------------
struct EvalFlags {
  std::string input;
  std::string quantity = "rgb";
  std::vector<double> wavelengths;
};

int run_eval(const ModelFlags& mf, const EvalFlags& ef) {
  const bool spectral = ef.quantity == "spectral";
  if (spectral && ef.wavelengths.empty())
    throw sl::InvalidArgument("--quantity spectral needs --wavelengths NM[,NM...]");
  if (!spectral && !ef.wavelengths.empty())
    throw sl::InvalidArgument("--wavelengths is only used with --quantity spectral");
  const auto model = mf.make();
  report_domain(*model);
  if (spectral && !sl::find_model(mf.model)->spectral)
    throw sl::InvalidArgument(
        fmt::format("--quantity spectral: model '{}' has no spectral output", mf.model));

  std::ifstream file;
  std::istream* in = &std::cin;
  const std::string source = ef.input.empty() || ef.input == "-" ? "<stdin>" : ef.input;
  if (!ef.input.empty() && ef.input != "-") {
    file.open(ef.input);
    if (!file)
      throw sl::IoError(fmt::format("cannot read '{}': no such file or not readable", ef.input));
    in = &file;
  }
  std::string line;
  std::size_t line_no = 0;
  auto next_line = [&]() -> bool {
    while (std::getline(*in, line)) {
      ++line_no;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (!line.empty()) return true;
    }
    return false;
  };
  if (!next_line())
    throw sl::InvalidArgument(
        fmt::format("{}: empty input, expected header 'zenith_deg,azimuth_deg'", source));
  if (line != "zenith_deg,azimuth_deg")
    throw sl::InvalidArgument(fmt::format(
        "{} line {}: header must be 'zenith_deg,azimuth_deg', got '{}'", source, line_no, line));
  std::string header = line;
  if (ef.quantity == "rgb")
    header += ",r,g,b";
  else if (ef.quantity == "xyz")
    header += ",x,y,z";
  else if (ef.quantity == "luminance")
    header += ",luminance";
  else
    for (double nm : ef.wavelengths) header += fmt::format(",L{}", nm);
  std::string out = header + "\n";

  auto parse = [&](const std::string& field, const char* column, double min, double max) {
    double v = 0.0;
    std::size_t used = 0;
    try {
      v = std::stod(field, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != field.size() || !std::isfinite(v))
      throw sl::InvalidArgument(fmt::format("{} line {}: {} '{}' is not a finite number", source,
                                            line_no, column, field));
    if (v < min || v > max)
      throw sl::InvalidArgument(fmt::format("{} line {}: {} = {} is outside [{}, {}]", source,
                                            line_no, column, field, min, max));
    return v;
  };
  const bool sky = !mf.sun_only, sun = mf.include_sun || mf.sun_only;
  while (next_line()) {
    const auto comma = line.find(',');
    if (comma == std::string::npos || line.find(',', comma + 1) != std::string::npos)
      throw sl::InvalidArgument(
          fmt::format("{} line {}: expected 2 fields 'zenith_deg,azimuth_deg', got '{}'", source,
                      line_no, line));
    const std::string zs = line.substr(0, comma), as = line.substr(comma + 1);
    const double zen = parse(zs, "zenith_deg", 0.0, 180.0);
    const double az = parse(as, "azimuth_deg", -360.0, 360.0);
    const sl::Vec3 v =
        sl::direction_from_angles(sl::deg_to_rad(zen), sl::wrap_azimuth(sl::deg_to_rad(az)));
    out += line;
    if (spectral) {
      for (double nm : ef.wavelengths) {
        double L = 0.0;
        if (sky) {
          const auto s = model->spectral_radiance(v, nm);
          if (!s)
            throw sl::InvalidArgument(fmt::format(
                "--wavelengths: {} nm is outside the range of model '{}'", nm, mf.model));
          L += *s;
        }
        if (sun) {
          const auto s = model->sun_spectral_radiance(v, nm);
          if (!s)
            throw sl::InvalidArgument(fmt::format(
                "--wavelengths: {} nm is outside the sun's range of model '{}'", nm, mf.model));
          L += *s;
        }
        out += fmt::format(",{}", L);
      }
    } else {
      sl::Xyz c;
      if (sky) c = model->tristimulus(v);
      if (sun) {
        const sl::Xyz s = model->sun_tristimulus(v);
        c = {c.X + s.X, c.Y + s.Y, c.Z + s.Z};
      }
      if (ef.quantity == "xyz") {
        out += fmt::format(",{},{},{}", c.X, c.Y, c.Z);
      } else if (ef.quantity == "luminance") {
        out += fmt::format(",{}", c.Y);
      } else {
        const sl::Rgb rgb = (sky && !sun) ? model->rgb(v) : sl::xyz_to_linear_srgb(c);
        out += fmt::format(",{},{},{}", rgb.r, rgb.g, rgb.b);
      }
    }
    out += "\n";
  }
  // Written only once everything parsed: a bad row produces no partial output.
  std::cout << out << std::flush;
  return kExitOk;
}

// ---- bench --------------------------------------------------------------------------------------
struct BenchFlags {
  int width = 1024, height = 512, repeats = 7;
  std::vector<std::string> models{"preetham", "cie", "hosek"};
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

template <class F>
double median_seconds(int repeats, F&& f) {
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    const auto a = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count());
  }
  return median(std::move(t));
}

int run_bench(const ModelFlags& base, const BenchFlags& bf) {
  namespace r = sl::render;
  r::RenderSettings s;
  s.width = bf.width;
  s.height = bf.height;
  const auto dirs = r::pixel_directions(s);
  const std::size_t n = dirs.x.size();
  std::vector<float> X(n), Y(n), Z(n);
  const int threads = sl::thread_count();
  std::cout << fmt::format(
      "skylight bench: {}x{} equirect directions, median of {} runs, {} threads\n", bf.width,
      bf.height, bf.repeats, threads);
  std::cout << fmt::format("{:<10} {:>12} {:>12} {:>12} {:>10} {:>10}\n", "model", "scalar ms",
                           "batch1 ms", "batchN ms", "SIMD x", "threads x");
  for (const auto& name : bf.models) {
    ModelFlags mf = base;
    mf.model = name;
    if (name == "perez" && mf.perez.empty()) mf.perez = {-1.0, -0.32, 10.0, -3.0, 0.45};
    if (name == "perez" && !mf.zenith_luminance) mf.zenith_luminance = 5000.0;
    const auto model = mf.make();
    volatile float sink = 0.0f;
    // In-run baseline: the plain scalar loop of the same model (double precision, one thread).
    const double scalar = median_seconds(bf.repeats, [&] {
      float acc = 0.0f;
      for (std::size_t i = 0; i < n; ++i)
        acc += static_cast<float>(model->tristimulus({dirs.x[i], dirs.y[i], dirs.z[i]}).Y);
      sink = acc;
    });
    const double batch1 = median_seconds(bf.repeats, [&] {
      model->tristimulus_batch({dirs.x, dirs.y, dirs.z}, {X, Y, Z});
      sink = Y[n / 2];
    });
    const double batchN = median_seconds(bf.repeats, [&] {
      sl::tristimulus_parallel(*model, {dirs.x, dirs.y, dirs.z}, {X, Y, Z});
      sink = Y[n / 2];
    });
    (void)sink;
    std::cout << fmt::format("{:<10} {:>12.2f} {:>12.2f} {:>12.2f} {:>10.2f} {:>10.2f}\n", name,
                             1e3 * scalar, 1e3 * batch1, 1e3 * batchN, scalar / batch1,
                             batch1 / batchN);
  }
  std::cout << "SIMD x = scalar loop / batch on one thread; threads x = batch one thread / batch "
               "all threads\n";
  return kExitOk;
}

// ---- report -------------------------------------------------------------------------------------
struct ReportFlags {
  std::string output, measurements, write_synthetic;
  std::optional<double> sun_azimuth_deg, sun_elevation_deg;
  bool quick = false;
};

int run_report(const ReportFlags& f) {
  namespace r = sl::render;
  if (!f.write_synthetic.empty()) {
    if (!f.output.empty() || !f.measurements.empty() || f.sun_azimuth_deg || f.sun_elevation_deg ||
        f.quick)
      throw sl::InvalidArgument("--write-synthetic-measurements takes no other report flag");
    sl::io::write_text_file(f.write_synthetic,
                            sl::analysis::format_sky_scan(sl::analysis::synthetic_tregenza_scan(),
                                                          sl::analysis::synthetic_scan_comments()));
    std::cerr << fmt::format("skylight report: wrote the synthetic scan to {}\n",
                             f.write_synthetic);
    return kExitOk;
  }
  if (f.output.empty()) throw sl::InvalidArgument("report: -o/--output DIR is required");
  if (f.sun_azimuth_deg.has_value() != f.sun_elevation_deg.has_value())
    throw sl::InvalidArgument("--sun-azimuth and --sun-elevation must be given together");
  sl::report::ReportOptions o;
  o.output_dir = f.output;
  if (!f.measurements.empty()) o.measurements = f.measurements;
  if (f.sun_azimuth_deg)
    o.measurement_sun_azimuth = sl::wrap_azimuth(sl::deg_to_rad(*f.sun_azimuth_deg));
  if (f.sun_elevation_deg) o.measurement_sun_elevation = sl::deg_to_rad(*f.sun_elevation_deg);
  o.quick = f.quick;
  // A progress bar on a terminal; one line per step otherwise (logs, CI).
  const bool tty = ::isatty(STDERR_FILENO) != 0;
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  o.progress = [&](int done, int total, std::string_view step) {
    if (tty) {
      constexpr int kBar = 30;
      const int filled = total > 0 ? done * kBar / total : kBar;
      std::cerr << fmt::format("\r\x1b[K[{}{}] {:>2}/{} {:5.1f} s  {}", std::string(filled, '#'),
                               std::string(kBar - filled, ' '), done, total, elapsed(), step)
                << std::flush;
      if (done == total) std::cerr << "\n";
    } else {
      std::cerr << fmt::format("skylight report: [{}/{}] {:.1f} s {}\n", done, total, elapsed(),
                               step);
    }
  };
  const sl::report::ReportSummary s = sl::report::write_report(o);
  std::cerr << fmt::format("skylight report: wrote {} files to {} in {:.1f} s\n", s.files.size(),
                           f.output, elapsed());
  std::cout << fmt::format("{}\n", (std::filesystem::path(f.output) / "index.html").string());
  return kExitOk;
}

std::string join_registry_names() {
  std::string names;
  for (const auto& m : sl::model_registry()) names += (names.empty() ? "" : ", ") + m.name;
  return names;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"skylight: daylight sky models, renders and checks"};
  app.set_version_flag("--version", std::string("skylight ") + sl::kVersion);
  app.require_subcommand(1);
  int threads = 0;
  app.add_option("--threads", threads,
                 "worker threads, 1-1024; default: SKYLIGHT_THREADS or all cores")
      ->check(CLI::Range(1, 1024));

  // Global options (--threads) are accepted after the subcommand too.
  app.fallthrough();
  bool models_json = false;
  auto* models = app.add_subcommand(
      "models", "list the models, their parameters (unit, range, default) and domains");
  models->add_flag("--json", models_json, "machine-readable JSON");

  ModelFlags render_mf;
  RenderFlags rf;
  auto* render = app.add_subcommand(
      "render", "render a sky into an image (EXR, HDR, PFM or PNG by extension)");
  render_mf.add(*render, true);
  render
      ->add_option("--projection", rf.projection,
                   "equirect|hemisphere|fisheye|cubemap|camera (perspective, e.g. of the planet "
                   "from orbit with --observer-altitude); default equirect")
      ->check(CLI::IsMember({"equirect", "hemisphere", "fisheye", "cubemap", "camera"}));
  render
      ->add_option(
          "--lens", rf.lens,
          "fisheye lens equidistant|equisolid|orthographic|stereographic; default equidistant")
      ->check(CLI::IsMember({"equidistant", "equisolid", "orthographic", "stereographic"}));
  render
      ->add_option("--fov", rf.fov_deg,
                   "fisheye field of view [deg], (0, 360] (orthographic <= 180); camera: "
                   "vertical field of view, (0, 180); default 180 (camera: 60)")
      ->check(finite_range(1e-6, 360, "deg"));
  render
      ->add_option("--look-elevation", rf.look_elevation_deg,
                   "camera: elevation of the view centre [deg], -90-90; default 0")
      ->check(finite_range(-90, 90, "deg"));
  render
      ->add_option("--look-azimuth", rf.look_azimuth_deg,
                   "camera: azimuth of the view centre [deg] from north towards east, -360-360; "
                   "default 0")
      ->check(finite_range(-360, 360, "deg"));
  render
      ->add_option(
          "--north-angle", rf.north_angle_deg,
          "fisheye: north drawn this many deg counter-clockwise from image up, -360-360; default 0")
      ->check(finite_range(-360, 360, "deg"));
  render
      ->add_option("--width", rf.width,
                   "image width [px], 1-32768; default 1024 (cubemap: 6 x height)")
      ->check(CLI::Range(1, 32768));
  render->add_option("--height", rf.height, "image height [px], 1-32768; default 512")
      ->check(CLI::Range(1, 32768));
  render
      ->add_option("-o,--output", rf.output,
                   "output image: .exr (float + metadata), .hdr, .pfm or .png (preview)")
      ->required();
  render->add_option("--preview", rf.preview, "also write a tone-mapped PNG preview here");
  render->add_option("--false-colour", rf.false_colour,
                     "also write a log-luminance false-colour PNG with legend here");
  render
      ->add_option(
          "--false-colour-range", rf.fc_range,
          "log10 luminance range LO,HI [log10 cd/m^2] of the false-colour scale; default 0,6")
      ->delimiter(',')
      ->expected(2)
      ->check(finite_range(-20, 20, "log10 cd/m^2"));

  ModelFlags eval_mf;
  EvalFlags ef;
  auto* eval = app.add_subcommand(
      "eval", "evaluate a model for directions read as CSV (zenith_deg,azimuth_deg)");
  eval_mf.add(*eval, true);
  eval->add_option("--input", ef.input, "input CSV file; default: standard input");
  eval->add_option("--quantity", ef.quantity,
                   "rgb (linear sRGB), xyz (Y in cd/m^2), luminance (cd/m^2), spectral (W m^-2 "
                   "sr^-1 nm^-1); default rgb")
      ->check(CLI::IsMember({"rgb", "xyz", "luminance", "spectral"}));
  eval->add_option("--wavelengths", ef.wavelengths,
                   "wavelengths [nm] for --quantity spectral, 1-10000, e.g. 450,550,650")
      ->delimiter(',')
      ->check(finite_range(1, 10000, "nm"));

  ModelFlags bench_mf;
  BenchFlags bf;
  auto* bench = app.add_subcommand(
      "bench", "time the batch path against an in-run scalar loop (ratios, medians)");
  bench->add_option("--width", bf.width, "grid width, 1-32768; default 1024")
      ->check(CLI::Range(1, 32768));
  bench->add_option("--height", bf.height, "grid height, 1-32768; default 512")
      ->check(CLI::Range(1, 32768));
  bench
      ->add_option("--repeats", bf.repeats,
                   "runs per measurement (median reported), 1-1000; default 7")
      ->check(CLI::Range(1, 1000));
  bench->add_option("--models", bf.models, "models to time; default preetham,cie,hosek")
      ->delimiter(',');

  ReportFlags repf;
  auto* report = app.add_subcommand(
      "report", "write the validation and comparison report (HTML + SVG/PNG + report.json)");
  report->add_option("-o,--output", repf.output,
                     "output directory (created if needed): index.html, report.json, figures");
  report->add_option("--measurements", repf.measurements,
                     "sky-luminance scan CSV (azimuth_deg,elevation_deg,luminance_cd_m2); "
                     "default: the shipped synthetic example");
  report
      ->add_option("--sun-azimuth", repf.sun_azimuth_deg,
                   "sun azimuth of the scan [deg] from north towards east, -360-360 (overrides "
                   "the file's '# sun_azimuth_deg')")
      ->check(finite_range(-360, 360, "deg"));
  report
      ->add_option("--sun-elevation", repf.sun_elevation_deg,
                   "sun elevation of the scan [deg], 0-90 (overrides the file's '# "
                   "sun_elevation_deg')")
      ->check(finite_range(0, 90, "deg"));
  report->add_flag("--quick", repf.quick,
                   "reduced resolution and fewer sun positions (seconds; for tests)");
  report->add_option("--write-synthetic-measurements", repf.write_synthetic,
                     "only write the synthetic example scan (CIE type 7 at the 145 Tregenza "
                     "patches, 5 % noise, fixed seed) to this CSV file");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string msg = e.what();
    std::replace(msg.begin(), msg.end(), '\n', ' ');
    std::cerr << "skylight: error: " << msg << " (see --help)\n";
    return kExitUsage;
  }

  try {
    if (const char* env = std::getenv("SKYLIGHT_THREADS")) {
      char* end = nullptr;
      const long v = std::strtol(env, &end, 10);
      if (*env == '\0' || *end != '\0' || v < 1 || v > 1024)
        throw sl::InvalidArgument(
            fmt::format("SKYLIGHT_THREADS = '{}' is not an integer in [1, 1024]", env));
    }
    if (threads > 0) sl::set_thread_count(threads);
    if (models->parsed()) return run_models(models_json);
    if (render->parsed()) return run_render(render_mf, rf);
    if (eval->parsed()) return run_eval(eval_mf, ef);
    if (report->parsed()) return run_report(repf);
    if (bench->parsed()) {
      for (const auto& m : bf.models)
        if (!sl::find_model(m))
          throw sl::InvalidArgument(
              fmt::format("--models: unknown model '{}' (known: {})", m, join_registry_names()));
      return run_bench(bench_mf, bf);
    }
  } catch (const sl::InvalidArgument& e) {
    std::cerr << "skylight: error: " << e.what() << "\n";
    return kExitUsage;
  } catch (const std::exception& e) {
    std::cerr << "skylight: error: " << e.what() << "\n";
    return kExitRuntime;
  }
  return kExitUsage;
}
