// `skylight haze`: aerial perspective after Morales, Oishi & Ikeuchi 2017 (haze/; docs/HAZE.md):
// scattering coefficients, the attenuation factor of a camera, the camera list, add / retarget /
// remove haze on an image with a depth map or composite a virtual object into a hazy photo
// (`--gpu`: by the fragment shaders of gpu/haze.h), and the watershed sky mask of a sky photo.
// The options are haze/request.h's (their schemas, the airlight's source, the settings).
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common.h"
#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/haze/attenuation.h"
#include "skylight/haze/request.h"
#include "skylight/io/camera_calibration.h"
#include "skylight/io/image.h"
#include "skylight/operations/operations.h"
#include "skylight/version.h"
#ifdef SKYLIGHT_HAVE_GPU
#include "skylight/gpu/haze.h"
#endif

namespace skylight::cli {
namespace {

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

// One haze subcommand: its operation's flags and its files.
struct HazeCommand {
  SchemaFlags flags;
  std::string image, depth, output;                // add, retarget, remove
  std::string object, object_depth, object_alpha;  // composite (--background is `image`)
  bool json = false;

  haze::Atmosphere atmosphere() const {
    const haze::Atmosphere a = flags.bind(haze::atmosphere_schema(), {}, "haze");
    haze::validate(a);
    return a;
  }
  haze::CameraSensitivity sensitivity() const {
    return flags.bind(haze::SensitivityOptions::schema(), {}, "haze").sensitivity();
  }
  haze::AirlightOptions airlight() const {
    return flags.bind(haze::AirlightOptions::schema(), {}, "haze");
  }
  std::string sky_path() const { return airlight().sky_photo; }
  ImageOptions sky_image() const { return airlight().sky_image; }
  bool gpu() const { return flags.values().has("gpu"); }
};

// The output is a float image. (That it replaces no input is the command's transaction's check,
// io::OutputTransaction.)
void check_output(const std::string& out) {
  if (out.empty()) throw InvalidArgument("give -o OUT");
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

int run_coefficients(const HazeCommand& f) {
  const haze::Atmosphere a = f.atmosphere();
  const double wavelength_nm =
      f.flags.bind(haze::CoefficientsOptions::schema(), {}, "haze coefficients").wavelength_nm;
  haze::validate(a);
  constexpr double kPerKm = 1e3;
  const double br = haze::rayleigh_per_m(wavelength_nm, a.altitude_m, a.variant) * kPerKm;
  const double bm = haze::mie_per_m(wavelength_nm, a.turbidity, a.altitude_m, a.variant) * kPerKm;
  // Table 2 classifies at standard conditions: 550 nm, sea level.
  const double bm_standard = haze::mie_per_m(550.0, a.turbidity, 0.0, a.variant) * kPerKm;
  const std::string weather = haze::weather_class(bm_standard);
  nlohmann::ordered_json j;
  j["variant"] = haze::to_string(a.variant);
  j["turbidity"] = a.turbidity;
  j["wavelength_nm"] = wavelength_nm;
  j["altitude_m"] = a.altitude_m;
  j["beta_rayleigh_per_km"] = br;
  j["beta_mie_per_km"] = bm;
  j["beta_total_per_km"] = br + bm;
  j["beta_mie_standard_per_km"] = bm_standard;
  j["weather_class"] = weather;
  const std::string text = fmt::format(
      "variant        {}\nbeta_rayleigh  {:.6g} /km\nbeta_mie       {:.6g} /km\nbeta_total     "
      "{:.6g} /km\nweather class  {} (beta_mie {:.4g} /km at 550 nm, 0 m; Table 2)\n",
      haze::to_string(a.variant), br, bm, br + bm, weather, bm_standard);
  write_stdout(json_or_text(f.json, j, text));
  return kExitOk;
}

int run_attenuation(const HazeCommand& f) {
  const haze::CameraSensitivity cam = f.sensitivity();
  const haze::Atmosphere air = f.atmosphere();
  const double distance_m =
      f.flags.bind(haze::AttenuationOptions::schema(), {}, "haze attenuation").distance_m;
  const haze::Attenuation att(air, cam);
  const haze::Rgb3 g = att.gamma(distance_m);
  nlohmann::ordered_json j;
  j["camera"] = cam.name;
  j["variant"] = haze::to_string(air.variant);
  j["turbidity"] = air.turbidity;
  j["altitude_m"] = air.altitude_m;
  j["distance_m"] = distance_m;
  j["gamma"] = {g[0], g[1], g[2]};
  write_stdout(json_or_text(f.json, j,
                            fmt::format("Gamma r g b  {:.6f} {:.6f} {:.6f}  ({}, {} m)\n", g[0],
                                        g[1], g[2], cam.name, distance_m)));
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

int run_sky_mask(const HazeCommand& f) {
  if (io::format_from_path(f.output) != io::ImageFormat::png)
    throw InvalidArgument(fmt::format("-o '{}': the sky mask is an 8-bit .png", excerpt(f.output)));
  const io::ImageF photo = io::read_image(f.sky_path());
  const Camera cam = io::photo_camera(f.sky_image(), photo.width, photo.height);
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

int run_image(const HazeCommand& f, haze::HazeOperation op, std::string_view name) {
  check_gpu_available(f.gpu());
  // The options' errors before the files are read (the request binds them again).
  (void)f.airlight();
  check_output(f.output);
  (void)f.sensitivity();
  (void)f.atmosphere();
  const io::ImageF image = io::read_image(f.image);
  if (image.channels != 3)
    throw InvalidArgument(
        fmt::format("--image '{}' has one channel; haze needs R, G, B", excerpt(f.image)));
  const haze::ImageHazeRequest r =
      haze::image_haze_request(op, f.flags.values(), image.width, image.height);
  const haze::CameraSensitivity& cam = r.camera;
  const haze::Atmosphere& air = r.air;
  const haze::HazeOptions& options = r.options;
  const haze::HazeSettings& s = r.settings;
  const io::ImageF depth = haze::depth_in_metres(
      io::read_scalar_image(f.depth), {options.near_m, options.far_m}, image.width, image.height,
      fmt::format("--depth '{}'", excerpt(f.depth)));
  haze::HazeReport report;
  const io::ImageF out = f.gpu() ? apply_on_gpu(image, depth, cam, s, &report)
                                 : haze::apply_haze(image, depth, cam, s, &report);
  check_finite(out);
  io::write_image(f.output, out, haze::haze_metadata(name, air, cam, s));
  write_stdout(fmt::format(
      "haze {}: {}x{}, {} airlight, Gamma table {} entries (interpolation error <= {:.2g}), {} "
      "pixels with Gamma_s below {} -> {}\n",
      name, image.width, image.height, s.airlight_source_map ? "per-pixel" : "constant",
      report.table_entries, report.table_error_bound, report.clamped_transmission_pixels,
      s.min_transmission, f.output));
  return kExitOk;
}

int run_composite(const HazeCommand& f) {
  check_gpu_available(f.gpu());
  // The options' errors before the files are read (the request binds them again).
  (void)f.airlight();
  check_output(f.output);
  (void)f.sensitivity();
  (void)f.atmosphere();
  const io::ImageF bg = io::read_image(f.image);
  const haze::ImageHazeRequest r =
      haze::image_haze_request(haze::HazeOperation::add, f.flags.values(), bg.width, bg.height);
  const haze::CameraSensitivity& cam = r.camera;
  const haze::Atmosphere& air = r.air;
  const haze::HazeOptions& options = r.options;
  const haze::HazeSettings& s = r.settings;
  const io::ImageF obj = io::read_image(f.object);
  const io::ImageF depth = haze::depth_in_metres(
      io::read_scalar_image(f.object_depth), {options.near_m, options.far_m}, obj.width, obj.height,
      fmt::format("--object-depth '{}'", excerpt(f.object_depth)));
  // No alpha: the object covers the pixels with depth > 0.
  const io::ImageF alpha = !f.object_alpha.empty() ? io::read_scalar_image(f.object_alpha)
                                                   : haze::coverage_from_depth(depth);
#ifdef SKYLIGHT_HAVE_GPU
  const io::ImageF out = f.gpu() ? gpu::composite(bg, obj, alpha, depth, cam, s)
                                 : haze::composite(bg, obj, alpha, depth, cam, s);
#else
  const io::ImageF out = haze::composite(bg, obj, alpha, depth, cam, s);
#endif
  check_finite(out);
  io::write_image(f.output, out, haze::haze_metadata("composite", air, cam, s));
  write_stdout(fmt::format("haze composite{}: {}x{} -> {}\n", f.gpu() ? " (GL)" : "", bg.width,
                           bg.height, f.output));
  return kExitOk;
}

// The flags of a subcommand from its operation, and the exclusions between them.
void add_operation_flags(CLI::App& cmd, HazeCommand& c, const std::string& operation) {
  c.flags.add(cmd, operations::find(operation).parameters);
  const auto excludes = [&](const char* a, const char* b) {
    if (c.flags.has(a) && c.flags.has(b)) c.flags.option(a)->excludes(c.flags.option(b));
  };
  excludes("camera", "camera-csv");
  excludes("airlight", "sky-model");
  excludes("airlight", "sky");
  excludes("sky-model", "sky");
  excludes("vfov", "hfov");
  for (const char* angle : {"heading", "pitch", "roll"}) excludes("view-matrix", angle);
  excludes("projection-matrix", "vfov");
  excludes("projection-matrix", "hfov");
  if (c.flags.has("sky-mask") && operation != "haze sky-mask")
    c.flags.option("sky-mask")->needs(c.flags.option("sky"));
  if (c.flags.has("turbidity")) c.flags.option("turbidity")->required();
  if (c.flags.has("target-turbidity")) c.flags.option("target-turbidity")->required();
}

}  // namespace

void add_haze_command(CLI::App& app, Commands& commands) {
  auto* haze = app.add_subcommand(
      "haze",
      "aerial perspective: add, remove or retarget the haze of a photo\n"
      "Aerial perspective (Morales et al. 2017; docs/HAZE.md): scattering coefficients, "
      "attenuation, cameras, add/retarget/remove haze on an image with depth, composite, "
      "sky-mask.");
  haze->require_subcommand(1);

  auto cf = std::make_shared<HazeCommand>();
  auto* coeff = haze->add_subcommand(
      "coefficients",
      "Rayleigh and Mie scattering coefficients and the weather class\n"
      "Rayleigh and Mie scattering coefficients of air of turbidity T and the weather class "
      "(Morales et al. 2017 Table 2).");
  add_operation_flags(*coeff, *cf, "haze coefficients");
  coeff->add_flag("--json", cf->json, "write JSON");
  commands.push_back({coeff, [cf] { return run_coefficients(*cf); }});

  auto af = std::make_shared<HazeCommand>();
  auto* att = haze->add_subcommand(
      "attenuation",
      "the attenuation of a horizontal path for a camera\n"
      "The attenuation factor Gamma_c (Morales et al. 2017 eq. 11) of a horizontal path for a "
      "camera.");
  add_operation_flags(*att, *af, "haze attenuation");
  af->flags.option("distance")->required();
  att->add_flag("--json", af->json, "write JSON");
  commands.push_back({att, [af] { return run_attenuation(*af); }});

  auto json_cameras = std::make_shared<bool>(false);
  auto* cams = haze->add_subcommand("cameras", "the embedded camera spectral sensitivities");
  cams->add_flag("--json", *json_cameras, "write JSON");
  commands.push_back({cams, [json_cameras] { return run_cameras(*json_cameras); }});

  const std::tuple<const char*, haze::HazeOperation, const char*> ops[] = {
      {"add", haze::HazeOperation::add, "add haze to an image with depth (eq. 10)"},
      {"retarget", haze::HazeOperation::retarget, "re-target haze from T to T_t (eq. 26)"},
      {"remove", haze::HazeOperation::remove, "remove haze (eq. 10 inverted)"}};
  for (const auto& [name, op, description] : ops) {
    auto f = std::make_shared<HazeCommand>();
    auto* cmd = haze->add_subcommand(name, description);
    cmd->add_option("--image", f->image, "the photo (.exr, .pfm, .hdr; linear RGB)")->required();
    cmd->add_option("--depth", f->depth,
                    "depth of every pixel: .exr (Z, Y or R), .pfm or 16-bit .png; metres, or "
                    "normalised with --near/--far (eq. 19)")
        ->required();
    add_operation_flags(*cmd, *f, std::string("haze ") + name);
    cmd->add_option("-o,--output", f->output, "output image (.exr, .pfm or .hdr)")->required();
    const std::string op_name = name;
    commands.push_back({cmd, [f, op = op, op_name] { return run_image(*f, op, op_name); }});
  }

  auto sm = std::make_shared<HazeCommand>();
  auto* mask_cmd = haze->add_subcommand(
      "sky-mask",
      "the sky of a photo as a mask\n"
      "The sky of a photo by a marker-controlled watershed (the segmentation of Morales et al. "
      "2017 eq. 12).");
  add_operation_flags(*mask_cmd, *sm, "haze sky-mask");
  sm->flags.option("sky")->required();
  mask_cmd->add_option("-o,--output", sm->output, "the mask: 8-bit .png, 255 = sky")->required();
  commands.push_back({mask_cmd, [sm] { return run_sky_mask(*sm); }});

  auto comp = std::make_shared<HazeCommand>();
  auto* c = haze->add_subcommand(
      "composite",
      "a virtual object given haze, over a background photo\n"
      "A virtual object (RGB + depth) given the haze of turbidity T, over a background photo.");
  c->add_option("--background", comp->image, "the background photo (.exr, .pfm, .hdr; linear RGB)")
      ->required();
  c->add_option("--object", comp->object, "the virtual object's RGB without haze")->required();
  c->add_option("--object-depth", comp->object_depth,
                "its depth: .exr (Z, Y or R), .pfm or 16-bit .png; metres, or normalised with "
                "--near/--far")
      ->required();
  c->add_option("--object-alpha", comp->object_alpha,
                "its coverage in [0, 1] (one channel); default 1 where the depth is > 0");
  add_operation_flags(*c, *comp, "haze composite");
  c->add_option("-o,--output", comp->output, "output image (.exr, .pfm or .hdr)")->required();
  commands.push_back({c, [comp] { return run_composite(*comp); }});
}

}  // namespace skylight::cli
