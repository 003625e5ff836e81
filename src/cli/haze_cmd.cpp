// `skylight haze`: aerial perspective after Morales, Oishi & Ikeuchi 2017 (haze/; docs/HAZE.md):
// scattering coefficients, the attenuation factor of a camera, the camera list, add / retarget /
// remove haze on an image with a depth map or composite a virtual object into a hazy photo
// (`--gpu`: by the fragment shaders of gpu/haze.h), and the watershed sky mask of a sky photo.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common.h"
#include "haze_camera.h"
#include "skylight/core/camera.h"
#include "skylight/core/error.h"
#include "skylight/core/frame.h"
#include "skylight/core/math.h"
#include "skylight/core/numbers.h"
#include "skylight/haze/airlight_field.h"
#include "skylight/haze/attenuation.h"
#include "skylight/haze/coefficients.h"
#include "skylight/haze/image_haze.h"
#include "skylight/haze/sky_segmentation.h"
#include "skylight/io/image.h"
#include "skylight/version.h"
#ifdef SKYLIGHT_HAVE_GPU
#include "skylight/gpu/haze.h"
#endif

namespace skylight::cli {
namespace {

namespace fs = std::filesystem;

// ---- shared flags ---------------------------------------------------------------------------

// `--gpu` needs the GPU module: said before any input is read.
void check_gpu_available(bool gpu) {
#ifdef SKYLIGHT_HAVE_GPU
  (void)gpu;
#else
  if (gpu)
    throw std::runtime_error(
        "--gpu: this skylight was built without the GPU module (SKYLIGHT_GPU=OFF: EGL and OpenGL "
        "were not found when configuring; docs/GPU.md)");
#endif
}

// A sky photo and its camera (--sky, --sky-projection and the fisheye flags).
struct SkyPhotoFlags {
  std::string path, projection = "fisheye";
  FisheyeFlags fisheye;
  void add_projection(CLI::App& cmd) {
    cmd.add_option("--sky-projection", projection, "--sky: fisheye|equirect; default fisheye")
        ->check(CLI::IsMember({"fisheye", "equirect"}));
    fisheye.add(cmd, "180", "--sky fisheye: field of view across the image circle");
  }
  Camera camera(const io::ImageF& photo) const {
    return image_camera(*parse_projection(projection), fisheye.layout(), photo.width, photo.height);
  }
};

const ParameterSpec& turbidity_spec() {
  static const ParameterSpec s{"turbidity",
                               "1",
                               ParameterKind::number,
                               1.0,
                               64.0,
                               1,
                               Required{},
                               "turbidity T of the air (Morales 2017 eq. 5; 1 = pure air)"};
  return s;
}

const ParameterSpec& altitude_spec() {
  static const ParameterSpec s{"altitude",
                               "m",
                               ParameterKind::number,
                               -500.0,
                               20000.0,
                               1,
                               ParameterValue(0.0),
                               "observer altitude h0 above sea level (horizontal paths at h0)"};
  return s;
}

struct AirFlags {
  double turbidity = 2.0, altitude_m = 0.0;
  std::string variant = "improved";
  void add(CLI::App& cmd) {
    add_number(cmd, turbidity_spec(), turbidity)->required();
    add_number(cmd, altitude_spec(), altitude_m);
    cmd.add_option("--variant", variant,
                   "scattering coefficients: improved (Morales 2017 eqs. 15, 18), preetham or "
                   "zhao; default improved")
        ->check(CLI::IsMember({"improved", "preetham", "zhao"}));
  }
  haze::Atmosphere atmosphere() const {
    return {turbidity, altitude_m, haze::parse_scattering_variant(variant)};
  }
};

struct CameraFlags {
  std::string name, csv;
  void add(CLI::App& cmd) {
    auto* n = cmd.add_option("--camera", name,
                             "camera spectral sensitivity by name (skylight haze cameras)");
    auto* c = cmd.add_option("--camera-csv", csv, "camera sensitivities: CSV 'nm,r,g,b'");
    n->excludes(c);
  }
  haze::CameraSensitivity camera() const {
    if (!csv.empty()) return haze::load_camera_csv(csv);
    if (name.empty()) throw InvalidArgument("give --camera NAME or --camera-csv FILE");
    return haze::find_camera(name);
  }
};

// The airlight I^inf: constant, or a sky model seen through the camera.
struct AirlightFlags {
  std::vector<double> airlight;
  std::string sky_model, sky_mask, horizon_region = "watershed";
  SkyPhotoFlags sky;
  mutable std::optional<haze::PhotoAirlight> photo;  // the horizon region of --sky, read once
  double sun_zenith_deg = kDefaultSunZenithDeg, sun_azimuth_deg = kDefaultSunAzimuthDeg;
  double view_elevation_deg = 0.0, view_azimuth_deg = 0.0;
  CLI::Option *view_elevation = nullptr, *view_azimuth = nullptr;
  void add(CLI::App& cmd) {
    auto* a = add_numbers(
        cmd,
        {"airlight", "image units", ParameterKind::numbers, 1e-30, 1e30, 3,
         Absent{"from --sky-model"}, "constant airlight I^inf R,G,B (Morales 2017 eq. 10), > 0"},
        airlight);
    auto* m = cmd.add_option("--sky-model", sky_model,
                             "airlight from a spectral sky model (preetham, hosek, nishita) at the "
                             "turbidity, seen through the camera (eq. 7)");
    auto* sky_photo = cmd.add_option(
        "--sky", sky.path,
        "airlight from a sky photo's horizon region (eqs. 12-13): linear .exr, .hdr or .pfm");
    a->excludes(m)->excludes(sky_photo);
    m->excludes(sky_photo);
    sky.add_projection(cmd);
    cmd.add_option("--horizon-region", horizon_region,
                   "--sky: the horizon region over the watershed sky mask (the band above the "
                   "skyline) or the fixed band above the horizon; default watershed (docs/HAZE.md)")
        ->check(CLI::IsMember({"watershed", "band"}));
    cmd.add_option("--sky-mask", sky_mask,
                   "--sky: its sky mask (.png, .pfm, .exr; nonzero = sky, e.g. from `skylight haze "
                   "sky-mask`) instead of the watershed")
        ->needs(sky_photo);
    ParameterSpec zenith = sun_parameter_specs()[0], azimuth = sun_parameter_specs()[1];
    add_number(cmd, zenith, sun_zenith_deg);
    add_number(cmd, azimuth, sun_azimuth_deg);
    view_elevation = add_number(
        cmd,
        {"view-elevation", "deg", ParameterKind::number, 0.0, 90.0, 1, ParameterValue(0.0),
         "--sky-model, --sky without an image camera: elevation of the sky seen behind the scene"},
        view_elevation_deg);
    view_azimuth = add_number(
        cmd,
        {"view-azimuth", "deg", ParameterKind::number, -360.0, 360.0, 1, ParameterValue(0.0),
         "--sky-model without an image camera: azimuth of that direction "
         "(north 0, east 90)"},
        view_azimuth_deg);
  }
  // The sky photo's horizon region (eq. 12) at turbidity `t`, its airlight for zenith `theta`.
  // The region (watershed or band, haze/sky_segmentation.h) is found once; only zeta depends on t
  // and theta.
  haze::PhotoAirlight photo_horizon(double t, double theta) const {
    if (!photo) {
      const io::ImageF image = io::read_image(sky.path);
      const Camera cam = sky.camera(image);
      haze::HorizonSettings h;
      if (horizon_region == "band") {
        if (!sky_mask.empty())
          throw InvalidArgument("--sky-mask goes with --horizon-region watershed");
        h.region = haze::HorizonRegion::band;
      }
      estimate::SkyMask mask;
      if (!sky_mask.empty()) {
        mask = haze::mask_from_image(estimate::load_mask(sky_mask), cam);
        h.mask = &mask;
      }
      photo = haze::photo_airlight(image, cam, t, theta, h);
    }
    haze::PhotoAirlight out = *photo;
    const double z = haze::zeta(t, theta, out.theta_prime);
    for (std::size_t c = 0; c < 3; ++c) out.airlight[c] = out.horizon[c] * z;
    return out;
  }
  std::unique_ptr<SkyModel> model_at(double t) const {
    const ModelInfo* info = find_model(sky_model);
    if (!info) throw InvalidArgument(fmt::format("unknown --sky-model '{}'", excerpt(sky_model)));
    SkyParameters p;
    p.sun = sun_from_degrees(sun_zenith_deg, sun_azimuth_deg);
    p.values = info->example;
    bool has_turbidity = false;
    for (const auto& spec : info->parameters) has_turbidity |= spec.name == "turbidity";
    if (!has_turbidity)
      throw InvalidArgument(fmt::format("--sky-model '{}' has no turbidity", sky_model));
    p.values.set("turbidity", t);
    return make_sky_model(sky_model, p);
  }
  // Per pixel at turbidity `t` through the image camera (Morales 2017 §6.2 step 3); null for a
  // constant --airlight.
  std::shared_ptr<const haze::AirlightMap> per_pixel(double t,
                                                     const haze::CameraSensitivity& camera,
                                                     const haze::ImagePositioning& image) const {
    if (view_elevation->count() > 0 || view_azimuth->count() > 0)
      throw InvalidArgument(
          "--view-elevation and --view-azimuth are for one airlight per image; with an image "
          "camera every pixel sees its own direction");
    if (!airlight.empty()) return nullptr;
    if (!sky.path.empty()) return haze::photo_airlight_map(image, photo_horizon(t, kPi / 2), t);
    const haze::AirlightTable table(*model_at(t), camera);
    return haze::sky_model_airlight_map(image, table);
  }
  // At turbidity `t`.
  haze::Rgb3 at(double t, const haze::CameraSensitivity& camera) const {
    if (!airlight.empty()) return {airlight[0], airlight[1], airlight[2]};
    const double theta = deg_to_rad(90.0 - view_elevation_deg);
    if (!sky.path.empty()) return photo_horizon(t, theta).airlight;
    if (sky_model.empty())
      throw InvalidArgument("give --airlight R,G,B, --sky PHOTO or --sky-model NAME");
    const auto model = model_at(t);
    const Vec3 view = direction_from_angles(theta, wrap_azimuth(deg_to_rad(view_azimuth_deg)));
    return haze::sky_model_airlight(*model, view, camera);
  }
};

// An output must not replace any input.
void check_output(const std::string& out, const std::vector<std::string>& inputs) {
  if (out.empty()) throw InvalidArgument("give -o OUT");
  std::error_code ec;
  for (const auto& in : inputs)
    if (!in.empty() && (in == out || fs::equivalent(in, out, ec)))
      throw InvalidArgument(
          fmt::format("-o '{}' is also an input; write to another file", excerpt(out)));
  if (io::format_from_path(out) == io::ImageFormat::png)
    throw InvalidArgument(
        fmt::format("-o '{}': write .exr, .pfm or .hdr (float data)", excerpt(out)));
}

void check_finite(const io::ImageF& image) {
  for (float v : image.data)
    if (!std::isfinite(v))
      throw InvalidArgument("the result holds a non-finite value; nothing was written");
}

std::string json_or_text(bool json, const nlohmann::ordered_json& j, const std::string& text) {
  return json ? j.dump(2) + "\n" : text;
}

// ---- coefficients, attenuation, cameras ----------------------------------------------------

struct CoefficientsFlags {
  AirFlags air;
  double wavelength_nm = 550.0;
  bool json = false;
};

int run_coefficients(const CoefficientsFlags& f) {
  const haze::Atmosphere a = f.air.atmosphere();
  haze::validate(a);
  constexpr double kPerKm = 1e3;
  const double br = haze::rayleigh_per_m(f.wavelength_nm, a.altitude_m, a.variant) * kPerKm;
  const double bm = haze::mie_per_m(f.wavelength_nm, a.turbidity, a.altitude_m, a.variant) * kPerKm;
  // Table 2 classifies at standard conditions: 550 nm, sea level.
  const double bm_standard = haze::mie_per_m(550.0, a.turbidity, 0.0, a.variant) * kPerKm;
  const std::string weather = haze::weather_class(bm_standard);
  nlohmann::ordered_json j;
  j["variant"] = f.air.variant;
  j["turbidity"] = a.turbidity;
  j["wavelength_nm"] = f.wavelength_nm;
  j["altitude_m"] = a.altitude_m;
  j["beta_rayleigh_per_km"] = br;
  j["beta_mie_per_km"] = bm;
  j["beta_total_per_km"] = br + bm;
  j["beta_mie_standard_per_km"] = bm_standard;
  j["weather_class"] = weather;
  const std::string text = fmt::format(
      "variant        {}\nbeta_rayleigh  {:.6g} /km\nbeta_mie       {:.6g} /km\nbeta_total     "
      "{:.6g} /km\nweather class  {} (beta_mie {:.4g} /km at 550 nm, 0 m; Table 2)\n",
      f.air.variant, br, bm, br + bm, weather, bm_standard);
  write_stdout(json_or_text(f.json, j, text));
  return kExitOk;
}

struct AttenuationFlags {
  AirFlags air;
  CameraFlags camera;
  double distance_m = 1000.0;
  bool json = false;
};

int run_attenuation(const AttenuationFlags& f) {
  const haze::CameraSensitivity cam = f.camera.camera();
  const haze::Attenuation att(f.air.atmosphere(), cam);
  const haze::Rgb3 g = att.gamma(f.distance_m);
  nlohmann::ordered_json j;
  j["camera"] = cam.name;
  j["variant"] = f.air.variant;
  j["turbidity"] = f.air.turbidity;
  j["altitude_m"] = f.air.altitude_m;
  j["distance_m"] = f.distance_m;
  j["gamma"] = {g[0], g[1], g[2]};
  write_stdout(json_or_text(f.json, j,
                            fmt::format("Gamma r g b  {:.6f} {:.6f} {:.6f}  ({}, {} m)\n", g[0],
                                        g[1], g[2], cam.name, f.distance_m)));
  return kExitOk;
}

int run_cameras(bool json) {
  nlohmann::ordered_json j = nlohmann::ordered_json::array();
  std::string text;
  for (const auto& name : haze::camera_names()) {
    const auto& cam = haze::find_camera(name);
    j.push_back({{"name", name}, {"camera", cam.description}});
    text += fmt::format("{:<28} {}\n", name, cam.description);
  }
  write_stdout(json ? j.dump(2) + "\n" : text);
  return kExitOk;
}

// ---- sky mask ----------------------------------------------------------------------------------

struct SkyMaskFlags {
  SkyPhotoFlags sky;
  std::string output;
};

int run_sky_mask(const SkyMaskFlags& f) {
  if (io::format_from_path(f.output) != io::ImageFormat::png)
    throw InvalidArgument(fmt::format("-o '{}': the sky mask is an 8-bit .png", excerpt(f.output)));
  std::error_code ec;
  if (f.output == f.sky.path || fs::equivalent(f.sky.path, f.output, ec))
    throw InvalidArgument(
        fmt::format("-o '{}' is also an input; write to another file", excerpt(f.output)));
  const io::ImageF photo = io::read_image(f.sky.path);
  const Camera cam = f.sky.camera(photo);
  const estimate::SkyMask mask = haze::segment_sky(photo, cam);
  io::write_png(f.output, haze::mask_image(mask),
                {{"Software", fmt::format("skylight {}", kVersion)},
                 {"Comment", "sky mask (watershed, Morales 2017 eq. 12): 255 = sky"}});
  write_stdout(fmt::format(
      "haze sky-mask: {}x{}, {} sky pixels ({:.1f} %) -> {}\n", photo.width, photo.height,
      mask.count,
      100.0 * static_cast<double>(mask.count) / (static_cast<double>(photo.width) * photo.height),
      f.output));
  return kExitOk;
}

// ---- image operations ------------------------------------------------------------------------

struct ImageFlags {
  haze::HazeOperation operation = haze::HazeOperation::add;
  std::string image, depth, output;
  std::optional<double> near_m, far_m, target_turbidity;
  double min_transmission = haze::kDefaultMinTransmission;
  bool gpu = false;  // add / retarget / remove on the headless GL context (gpu/haze.h)
  AirFlags air;
  CameraFlags camera;
  AirlightFlags airlight;
  HazeCameraFlags image_camera;  // per-pixel airlight (Morales 2017 eqs. 20-23)
  // composite
  std::string object, object_depth, object_alpha;
};

io::Metadata haze_metadata(const ImageFlags& f, const haze::CameraSensitivity& cam,
                           std::string_view op, const haze::HazeSettings& s) {
  io::Metadata md{
      {"skylight:version", kVersion},
      {"skylight:haze_operation", std::string(op)},
      {"skylight:camera", cam.name},
      {"skylight:scattering_variant", f.air.variant},
      {"skylight:turbidity", fmt::format("{}", f.air.turbidity)},
      {"skylight:altitude_m", fmt::format("{}", f.air.altitude_m)},
      {"skylight:airlight", s.airlight_source_map
                                ? std::string("per pixel")
                                : fmt::format("{},{},{}", s.airlight_source[0],
                                              s.airlight_source[1], s.airlight_source[2])}};
  if (s.target_turbidity)
    md.emplace_back("skylight:target_turbidity", fmt::format("{}", *s.target_turbidity));
  return md;
}

haze::HazeSettings settings_of(const ImageFlags& f, const haze::CameraSensitivity& cam) {
  haze::HazeSettings s;
  s.operation = f.operation;
  s.source = f.air.atmosphere();
  haze::validate(s.source);
  s.min_transmission = f.min_transmission;
  s.airlight_source = f.airlight.at(f.air.turbidity, cam);
  if (f.operation == haze::HazeOperation::retarget) {
    if (!f.target_turbidity) throw InvalidArgument("haze retarget needs --target-turbidity");
    s.target_turbidity = f.target_turbidity;
    s.airlight_target = f.airlight.at(*f.target_turbidity, cam);
  } else if (f.target_turbidity) {
    throw InvalidArgument("--target-turbidity is for haze retarget only");
  }
  return s;
}

// Clip planes of a pinhole image camera when the depth map holds metres (the pixels' directions do
// not depend on them) [m].
constexpr double kPinholeNearM = 1.0, kPinholeFarM = 1e4;

// With an image camera, --sky and --sky-model give every pixel the airlight of its own direction
// (Morales 2017 §6.2: eqs. 20-22, then eqs. 12-13 or the model); --airlight stays constant.
void add_per_pixel_airlight(const ImageFlags& f, const haze::CameraSensitivity& cam,
                            haze::HazeSettings& s, int width, int height) {
  const std::optional<haze::ImagePositioning> image = f.image_camera.positioning(
      width, height, f.near_m.value_or(kPinholeNearM), f.far_m.value_or(kPinholeFarM));
  if (!image) return;
  s.airlight_source_map = f.airlight.per_pixel(f.air.turbidity, cam, *image);
  if (s.airlight_source_map && s.target_turbidity)
    s.airlight_target_map = f.airlight.per_pixel(*s.target_turbidity, cam, *image);
}

// `--gpu`: the same operation by the fragment shader (gpu/haze.h; depth already in metres).
io::ImageF apply_on_gpu(const io::ImageF& image, const io::ImageF& depth_m,
                        const haze::CameraSensitivity& cam, const haze::HazeSettings& s,
                        haze::HazeReport* report) {
#ifdef SKYLIGHT_HAVE_GPU
  return gpu::apply_haze(image, depth_m, {}, cam, s, report);
#else
  (void)image, (void)depth_m, (void)cam, (void)s, (void)report;
  check_gpu_available(true);
  return {};
#endif
}

int run_image(const ImageFlags& f, std::string_view op) {
  check_gpu_available(f.gpu);
  check_output(f.output, {f.image, f.depth, f.airlight.sky.path, f.airlight.sky_mask});
  const haze::CameraSensitivity cam = f.camera.camera();
  haze::HazeSettings s = settings_of(f, cam);
  const io::ImageF image = io::read_image(f.image);
  if (image.channels != 3)
    throw InvalidArgument(
        fmt::format("--image '{}' has one channel; haze needs R, G, B", excerpt(f.image)));
  add_per_pixel_airlight(f, cam, s, image.width, image.height);
  const io::ImageF depth =
      haze::depth_in_metres(io::read_scalar_image(f.depth), {f.near_m, f.far_m}, image.width,
                            image.height, fmt::format("--depth '{}'", excerpt(f.depth)));
  haze::HazeReport report;
  const io::ImageF out = f.gpu ? apply_on_gpu(image, depth, cam, s, &report)
                               : haze::apply_haze(image, depth, cam, s, &report);
  check_finite(out);
  io::write_image(f.output, out, haze_metadata(f, cam, op, s));
  write_stdout(fmt::format(
      "haze {}: {}x{}, {} airlight, Gamma table {} entries (interpolation error <= {:.2g}), {} "
      "pixels with Gamma_s below {} -> {}\n",
      op, image.width, image.height, s.airlight_source_map ? "per-pixel" : "constant",
      report.table_entries, report.table_error_bound, report.clamped_transmission_pixels,
      s.min_transmission, f.output));
  return kExitOk;
}

int run_composite(const ImageFlags& f) {
  check_gpu_available(f.gpu);
  check_output(f.output, {f.image, f.object, f.object_depth, f.object_alpha, f.airlight.sky.path,
                          f.airlight.sky_mask});
  const haze::CameraSensitivity cam = f.camera.camera();
  haze::HazeSettings s = settings_of(f, cam);
  const io::ImageF bg = io::read_image(f.image);
  add_per_pixel_airlight(f, cam, s, bg.width, bg.height);
  const io::ImageF obj = io::read_image(f.object);
  const io::ImageF depth = haze::depth_in_metres(
      io::read_scalar_image(f.object_depth), {f.near_m, f.far_m}, obj.width, obj.height,
      fmt::format("--object-depth '{}'", excerpt(f.object_depth)));
  io::ImageF alpha;
  if (!f.object_alpha.empty()) {
    alpha = io::read_scalar_image(f.object_alpha);
  } else {  // no alpha: the object covers the pixels with depth > 0
    alpha = io::ImageF(depth.width, depth.height, 1);
    for (std::size_t i = 0; i < alpha.data.size(); ++i)
      alpha.data[i] = depth.data[i] > 0.0f ? 1.0f : 0.0f;
  }
#ifdef SKYLIGHT_HAVE_GPU
  const io::ImageF out = f.gpu ? gpu::composite(bg, obj, alpha, depth, cam, s)
                               : haze::composite(bg, obj, alpha, depth, cam, s);
#else
  const io::ImageF out = haze::composite(bg, obj, alpha, depth, cam, s);
#endif
  check_finite(out);
  io::write_image(f.output, out, haze_metadata(f, cam, "composite", s));
  write_stdout(fmt::format("haze composite{}: {}x{} -> {}\n", f.gpu ? " (GL)" : "", bg.width,
                           bg.height, f.output));
  return kExitOk;
}

void add_image_flags(CLI::App& cmd, ImageFlags& f, bool composite) {
  if (composite) {
    cmd.add_option("--background", f.image, "the background photo (.exr, .pfm, .hdr; linear RGB)")
        ->required();
    cmd.add_option("--object", f.object, "the virtual object's RGB without haze")->required();
    cmd.add_option("--object-depth", f.object_depth,
                   "its depth: .exr (Z, Y or R), .pfm or 16-bit .png; metres, or normalised with "
                   "--near/--far")
        ->required();
    cmd.add_option("--object-alpha", f.object_alpha,
                   "its coverage in [0, 1] (one channel); default 1 where the depth is > 0");
  } else {
    cmd.add_option("--image", f.image, "the photo (.exr, .pfm, .hdr; linear RGB)")->required();
    cmd.add_option("--depth", f.depth,
                   "depth of every pixel: .exr (Z, Y or R), .pfm or 16-bit .png; metres, or "
                   "normalised with --near/--far (eq. 19)")
        ->required();
  }
  f.air.add(cmd);
  if (!composite && f.operation == haze::HazeOperation::retarget)
    add_number(cmd,
               {"target-turbidity", "1", ParameterKind::number, 1.0, 64.0, 1, Required{},
                "turbidity T_t to re-target to (eq. 26)"},
               f.target_turbidity)
        ->required();
  f.camera.add(cmd);
  add_number(cmd,
             {"near", "m", ParameterKind::number, 1e-6, 1e9, 1,
              Absent{"the depth map holds metres"}, "near plane of a normalised depth map"},
             f.near_m);
  add_number(cmd,
             {"far", "m", ParameterKind::number, 1e-6, 1e9, 1, Absent{"the depth map holds metres"},
              "far plane of a normalised depth map"},
             f.far_m);
  f.airlight.add(cmd);
  f.image_camera.add(cmd);
  if (!composite)
    add_number(cmd,
               {"min-transmission", "1", ParameterKind::number, 1e-6, 1.0, 1,
                ParameterValue(f.min_transmission),
                "remove/retarget: Gamma_s is taken as at least this (bounds the amplification)"},
               f.min_transmission);
  cmd.add_flag("--gpu", f.gpu,
               "run the operation as a fragment shader on the headless GL context (docs/GPU.md)");
  cmd.add_option("-o,--output", f.output, "output image (.exr, .pfm or .hdr)")->required();
}

}  // namespace

void add_haze_command(CLI::App& app, Commands& commands) {
  auto* haze = app.add_subcommand(
      "haze",
      "aerial perspective (Morales et al. 2017): coefficients, attenuation, cameras, "
      "add/retarget/remove haze, composite, sky-mask");
  haze->require_subcommand(1);

  auto cf = std::make_shared<CoefficientsFlags>();
  auto* coeff = haze->add_subcommand(
      "coefficients", "Rayleigh and Mie scattering coefficients and the weather class (Table 2)");
  cf->air.add(*coeff);
  add_number(*coeff,
             {"wavelength", "nm", ParameterKind::number, 300.0, 1000.0, 1, ParameterValue(550.0),
              "wavelength"},
             cf->wavelength_nm);
  coeff->add_flag("--json", cf->json, "write JSON");
  commands.push_back({coeff, [cf] { return run_coefficients(*cf); }});

  auto af = std::make_shared<AttenuationFlags>();
  auto* att = haze->add_subcommand(
      "attenuation", "the attenuation factor Gamma_c (eq. 11) of a horizontal path for a camera");
  af->air.add(*att);
  af->camera.add(*att);
  add_number(*att,
             {"distance", "m", ParameterKind::number, 0.0, 1e7, 1, Required{}, "path length s"},
             af->distance_m)
      ->required();
  att->add_flag("--json", af->json, "write JSON");
  commands.push_back({att, [af] { return run_attenuation(*af); }});

  auto json_cameras = std::make_shared<bool>(false);
  auto* cams = haze->add_subcommand("cameras", "the embedded camera spectral sensitivities");
  cams->add_flag("--json", *json_cameras, "write JSON");
  commands.push_back({cams, [json_cameras] { return run_cameras(*json_cameras); }});

  const std::pair<const char*, haze::HazeOperation> ops[] = {
      {"add", haze::HazeOperation::add},
      {"retarget", haze::HazeOperation::retarget},
      {"remove", haze::HazeOperation::remove}};
  for (const auto& [name, op] : ops) {
    auto f = std::make_shared<ImageFlags>();
    f->operation = op;
    auto* cmd = haze->add_subcommand(
        name, op == haze::HazeOperation::add        ? "add haze to an image with depth (eq. 10)"
              : op == haze::HazeOperation::retarget ? "re-target haze from T to T_t (eq. 26)"
                                                    : "remove haze (eq. 10 inverted)");
    add_image_flags(*cmd, *f, false);
    const std::string op_name = name;
    commands.push_back({cmd, [f, op_name] { return run_image(*f, op_name); }});
  }

  auto sm = std::make_shared<SkyMaskFlags>();
  auto* mask_cmd = haze->add_subcommand(
      "sky-mask", "the sky of a photo by a marker-controlled watershed (eq. 12's segmentation)");
  mask_cmd->add_option("--sky", sm->sky.path, "the sky photo: linear .exr, .hdr or .pfm")
      ->required();
  sm->sky.add_projection(*mask_cmd);
  mask_cmd->add_option("-o,--output", sm->output, "the mask: 8-bit .png, 255 = sky")->required();
  commands.push_back({mask_cmd, [sm] { return run_sky_mask(*sm); }});

  auto comp = std::make_shared<ImageFlags>();
  auto* c = haze->add_subcommand(
      "composite", "a virtual object (RGB + depth) given the haze of T, over a background photo");
  add_image_flags(*c, *comp, true);
  commands.push_back({c, [comp] { return run_composite(*comp); }});
}

}  // namespace skylight::cli
