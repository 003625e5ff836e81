// `haze coefficients|attenuation|cameras|add|retarget|remove|composite|sky-mask`: aerial
// perspective after Morales, Oishi & Ikeuchi 2017 (haze/; docs/HAZE.md). The options are
// haze/request.h's; `--gpu` runs the image operations by the installed GL backend.
#include <fmt/format.h>

#include <cmath>

#include "skylight/haze/attenuation.h"
#include "skylight/haze/request.h"
#include "skylight/io/camera_calibration.h"
#include "skylight/operations/detail/families.h"
#include "skylight/operations/gpu_backend.h"
#include "skylight/operations/operations.h"
#include "skylight/version.h"

namespace skylight::operations::detail {
namespace {

// The option pairs no haze operation takes together, and the sky mask that belongs to a sky
// photo.
std::vector<Relation> haze_relations(const std::vector<ParameterSpec>& parameters,
                                     bool sky_mask_needs_sky) {
  const auto has = [&](const std::string& name) {
    for (const ParameterSpec& s : parameters)
      if (s.name == name) return true;
    return false;
  };
  std::vector<Relation> out;
  const auto add = [&](Relation r) {
    if (has(r.a) && has(r.b)) out.push_back(std::move(r));
  };
  add(excludes("camera", "camera-csv"));
  add(excludes("airlight", "sky-model"));
  add(excludes("airlight", "sky"));
  add(excludes("sky-model", "sky"));
  add(excludes("vfov", "hfov"));
  for (const char* angle : {"heading", "pitch", "roll"}) add(excludes("view-matrix", angle));
  add(excludes("projection-matrix", "vfov"));
  add(excludes("projection-matrix", "hfov"));
  if (sky_mask_needs_sky) add(needs("sky-mask", "sky"));
  return out;
}

// The files among the haze options: the camera's sensitivities and the sky photo with its mask.
void mark_haze_files(std::vector<ParameterSpec>& parameters) {
  for (ParameterSpec& s : parameters)
    if (s.name == "camera-csv" || s.name == "sky" || s.name == "sky-mask" ||
        s.name == "sky-calibration")
      s.file = FileRole::input;
}

OperationInfo haze_operation(OperationInfo op, bool sky_mask_needs_sky = true) {
  mark_haze_files(op.parameters);
  op.relations = haze_relations(op.parameters, sky_mask_needs_sky);
  return op;
}

// ---- coefficients, attenuation, cameras ---------------------------------------------------------

struct CoefficientsResult {
  haze::Atmosphere air{};
  double wavelength_nm = 0.0, rayleigh = 0.0, mie = 0.0, mie_standard = 0.0;
  std::string weather{};
};

const ResultSchema<CoefficientsResult>& coefficients_result() {
  using R = CoefficientsResult;
  static const ResultSchema<R> s = [] {
    ResultSchema<R> s;
    s.text("variant", "the scattering variant",
           [](const R& r) { return std::string(haze::to_string(r.air.variant)); })
        .number("turbidity", "1", "T", [](const R& r) { return r.air.turbidity; })
        .number("wavelength_nm", "nm", "the wavelength", &R::wavelength_nm)
        .number("altitude_m", "m", "the path's altitude",
                [](const R& r) { return r.air.altitude_m; })
        .number("beta_rayleigh_per_km", "1/km", "Rayleigh scattering (eq. 3 or 15)", &R::rayleigh,
                6)
        .number("beta_mie_per_km", "1/km", "Mie scattering (eq. 4 or 16)", &R::mie, 6)
        .number(
            "beta_total_per_km", "1/km", "their sum", [](const R& r) { return r.rayleigh + r.mie; },
            6)
        .number("beta_mie_standard_per_km", "1/km",
                "Mie at Table 2's standard conditions (550 nm, 0 m)", &R::mie_standard, 4)
        .text("weather_class", "Table 2's class of that value", &R::weather);
    return s;
  }();
  return s;
}

OperationInfo coefficients_operation() {
  OperationInfo op{.name = "haze coefficients",
                   .summary = "Rayleigh and Mie scattering coefficients and the weather class",
                   .description =
                       "Rayleigh and Mie scattering coefficients of air of turbidity T and the "
                       "weather class (Morales et al. 2017 Table 2)",
                   .parameters = concat({haze::atmosphere_schema().specs(),
                                         haze::CoefficientsOptions::schema().specs()}),
                   .result = coefficients_result().fields(),
                   .result_type = "per-km coefficients"};
  op.run = [](const Request& r, const ProgressSink&) {
    CoefficientsResult c;
    c.air = r.bind(haze::atmosphere_schema());
    haze::validate(c.air);
    c.wavelength_nm = r.bind(haze::CoefficientsOptions::schema()).wavelength_nm;
    constexpr double kPerKm = 1e3;
    c.rayleigh = haze::rayleigh_per_m(c.wavelength_nm, c.air.altitude_m, c.air.variant) * kPerKm;
    c.mie =
        haze::mie_per_m(c.wavelength_nm, c.air.turbidity, c.air.altitude_m, c.air.variant) * kPerKm;
    // Table 2 classifies at standard conditions: 550 nm, sea level.
    c.mie_standard = haze::mie_per_m(550.0, c.air.turbidity, 0.0, c.air.variant) * kPerKm;
    c.weather = haze::weather_class(c.mie_standard);
    Result out;
    out.record = coefficients_result().record(c);
    return out;
  };
  return haze_operation(op);
}

struct AttenuationResult {
  std::string camera{};
  haze::Atmosphere air{};
  double distance_m = 0.0;
  haze::Rgb3 gamma{};
};

const ResultSchema<AttenuationResult>& attenuation_result() {
  using R = AttenuationResult;
  static const ResultSchema<R> s = [] {
    ResultSchema<R> s;
    s.text("camera", "the camera's sensitivities", &R::camera)
        .text("variant", "the scattering variant",
              [](const R& r) { return std::string(haze::to_string(r.air.variant)); })
        .number("turbidity", "1", "T", [](const R& r) { return r.air.turbidity; })
        .number("altitude_m", "m", "the path's altitude",
                [](const R& r) { return r.air.altitude_m; })
        .number("distance_m", "m", "the path's length", &R::distance_m)
        .numbers(
            "gamma", "1", "Gamma_c (eq. 11) per camera channel r, g, b",
            [](const R& r) { return std::vector<double>(r.gamma.begin(), r.gamma.end()); }, 6);
    return s;
  }();
  return s;
}

OperationInfo attenuation_operation() {
  OperationInfo op{.name = "haze attenuation",
                   .summary = "the attenuation of a horizontal path for a camera",
                   .description =
                       "the attenuation factor Gamma_c (Morales et al. 2017 eq. 11) "
                       "of a horizontal path for a camera",
                   .parameters = concat({haze::atmosphere_schema().specs(),
                                         haze::SensitivityOptions::schema().specs(),
                                         haze::AttenuationOptions::schema().specs()}),
                   .result = attenuation_result().fields(),
                   .result_type = "haze::Rgb3"};
  for (ParameterSpec& s : op.parameters)
    if (s.name == "distance") s.default_value = Required{};
  op.run = [](const Request& r, const ProgressSink&) {
    AttenuationResult a;
    const haze::CameraSensitivity cam = r.bind(haze::SensitivityOptions::schema()).sensitivity();
    a.camera = cam.name;
    a.air = r.bind(haze::atmosphere_schema());
    a.distance_m = r.bind(haze::AttenuationOptions::schema()).distance_m;
    a.gamma = haze::Attenuation(a.air, cam).gamma(a.distance_m);
    Result out;
    out.record = attenuation_result().record(a);
    return out;
  };
  return haze_operation(op);
}

struct CameraRecord {
  std::string name{}, camera{};
};
struct CamerasResult {
  std::vector<CameraRecord> cameras{};
};

const ResultSchema<CamerasResult>& cameras_result() {
  static const ResultSchema<CamerasResult> s = [] {
    ResultSchema<CameraRecord> c;
    c.text("name", "what --camera takes", &CameraRecord::name)
        .text("camera", "the camera and the source of its sensitivities", &CameraRecord::camera);
    ResultSchema<CamerasResult> s;
    s.records("cameras", "the embedded camera spectral sensitivities", c, &CamerasResult::cameras);
    return s;
  }();
  return s;
}

OperationInfo cameras_operation() {
  OperationInfo op{.name = "haze cameras",
                   .summary = "the embedded camera spectral sensitivities",
                   .description =
                       "the camera spectral sensitivities embedded in the library "
                       "(--camera NAME of the haze operations)",
                   .result = cameras_result().fields(),
                   .result_type = "haze::CameraSensitivity per camera"};
  op.run = [](const Request&, const ProgressSink&) {
    CamerasResult c;
    for (const auto& name : haze::camera_names())
      c.cameras.push_back({name, haze::find_camera(name).description});
    Result out;
    out.record = cameras_result().record(c);
    return out;
  };
  return op;
}

// ---- image operations ---------------------------------------------------------------------------

struct ImageResult {
  std::string operation{};
  int width = 0, height = 0;
  bool per_pixel_airlight = false, gpu = false;
  long long table_entries = 0, clamped = 0;
  double table_error = 0.0, min_transmission = 0.0;
};

const ResultSchema<ImageResult>& image_result() {
  using R = ImageResult;
  static const ResultSchema<R> s = [] {
    ResultSchema<R> s;
    s.text("operation", "add, retarget, remove or composite", &R::operation)
        .integer("width", "px", "the image's width", &R::width)
        .integer("height", "px", "its height", &R::height)
        .text("airlight", "constant, or per-pixel through the image's camera",
              [](const R& r) { return r.per_pixel_airlight ? "per-pixel" : "constant"; })
        .text("renderer", "cpu or gpu", [](const R& r) { return r.gpu ? "gpu" : "cpu"; })
        .integer("gamma_table_entries", "1", "entries of the Gamma tables (eq. 11)",
                 &R::table_entries)
        .number("gamma_table_error", "1", "their interpolation bound", &R::table_error)
        .integer("pixels_below_min_transmission", "1",
                 "pixels with Gamma_s below min_transmission (floored there)", &R::clamped)
        .number("min_transmission", "1", "the floor of Gamma_s", &R::min_transmission);
    return s;
  }();
  return s;
}

void check_finite(const io::ImageF& image) {
  for (float v : image.data)
    if (!std::isfinite(v))
      throw InvalidArgument("the result holds a non-finite value; nothing was written");
}

// The options' errors that need no file (the request binds them again).
void check_image_options(Request& r) {
  (void)r.bind(haze::AirlightOptions::schema());
  (void)r.bind(haze::SensitivityOptions::schema()).sensitivity();
  haze::validate(r.bind(haze::atmosphere_schema()));
  if (r.given("gpu")) (void)gpu_backend("--gpu");
}

Result run_image(const Request& r, haze::HazeOperation op, const std::string& name) {
  const io::ImageF image = r.image("image");
  if (image.channels != 3)
    throw InvalidArgument(fmt::format("{} has one channel; haze needs R, G, B", r.source("image")));
  const haze::ImageHazeRequest q =
      haze::image_haze_request(op, r.values(), image.width, image.height);
  const io::ImageF depth =
      haze::depth_in_metres(r.scalar_image("depth"), {q.options.near_m, q.options.far_m},
                            image.width, image.height, r.source("depth"));
  haze::HazeReport report;
  const bool gpu = r.given("gpu");
  const io::ImageF out =
      gpu ? gpu_backend("--gpu").apply_haze(image, depth, q.camera, q.settings, &report)
          : haze::apply_haze(image, depth, q.camera, q.settings, &report);
  check_finite(out);
  Result res;
  r.write_image(res, "output", out, haze::haze_metadata(name, q.air, q.camera, q.settings));
  res.record = image_result().record({name, image.width, image.height,
                                      q.settings.airlight_source_map != nullptr, gpu,
                                      static_cast<long long>(report.table_entries),
                                      static_cast<long long>(report.clamped_transmission_pixels),
                                      report.table_error_bound, q.settings.min_transmission});
  return res;
}

std::vector<ParameterSpec> image_specs() {
  const auto& h = haze::HazeOptions::schema();
  return concat({haze::atmosphere_schema().specs(),
                 haze::SensitivityOptions::schema().specs(),
                 {*h.find("near"), *h.find("far")},
                 haze::AirlightOptions::schema().specs(),
                 haze::ImageCameraOptions::schema().specs()});
}

ParameterSpec gpu_image_spec() {
  return gpu_spec(
      "run the operation as a fragment shader on the headless GL context "
      "(docs/GPU.md)");
}

OperationInfo image_operation(haze::HazeOperation op, std::string name, std::string summary,
                              std::string description) {
  const auto& h = haze::HazeOptions::schema();
  std::vector<ParameterSpec> own{*h.find("min-transmission"), gpu_image_spec()};
  if (op == haze::HazeOperation::retarget) {
    ParameterSpec target = *h.find("target-turbidity");
    target.default_value = Required{};
    own.insert(own.begin(), target);
  }
  OperationInfo info{
      .name = "haze " + name,
      .summary = std::move(summary),
      .description = std::move(description),
      .parameters = concat(
          {{input_file("image", "the photo: linear RGB", kFloatImageFormats),
            input_file("depth",
                       "depth of every pixel: .exr (Z, Y or R), .pfm or 16-bit .png; metres, or "
                       "normalised with --near/--far (eq. 19)",
                       {".exr", ".pfm", ".png"})},
           image_specs(),
           own,
           {output_file("output", "the output image", kFloatImageFormats)}}),
      .result = image_result().fields(),
      .result_type = "io::ImageF"};
  info.check = check_image_options;
  info.run = [op, name](const Request& r, const ProgressSink&) { return run_image(r, op, name); };
  return haze_operation(info);
}

OperationInfo composite_operation() {
  OperationInfo info{
      .name = "haze composite",
      .summary = "a virtual object given haze, over a background photo",
      .description =
          "a virtual object (RGB + depth) given the haze of turbidity T, over a "
          "background photo",
      .parameters = concat(
          {{input_file("background", "the background photo: linear RGB", kFloatImageFormats),
            input_file("object", "the virtual object's RGB without haze", kFloatImageFormats),
            input_file("object-depth",
                       "its depth: .exr (Z, Y or R), .pfm or 16-bit .png; metres, or normalised "
                       "with --near/--far",
                       {".exr", ".pfm", ".png"}),
            input_file("object-alpha", "its coverage in [0, 1] (one channel)",
                       {".exr", ".pfm", ".png"}, "1 where the depth is > 0")},
           image_specs(),
           {gpu_image_spec(), output_file("output", "the output image", kFloatImageFormats)}}),
      .result = image_result().fields(),
      .result_type = "io::ImageF"};
  info.check = check_image_options;
  info.run = [](const Request& r, const ProgressSink&) {
    const io::ImageF bg = r.image("background");
    const haze::ImageHazeRequest q =
        haze::image_haze_request(haze::HazeOperation::add, r.values(), bg.width, bg.height);
    const io::ImageF obj = r.image("object");
    const io::ImageF depth =
        haze::depth_in_metres(r.scalar_image("object-depth"), {q.options.near_m, q.options.far_m},
                              obj.width, obj.height, r.source("object-depth"));
    // No alpha: the object covers the pixels with depth > 0.
    const io::ImageF alpha = r.has_input("object-alpha") ? r.scalar_image("object-alpha")
                                                         : haze::coverage_from_depth(depth);
    const bool gpu = r.given("gpu");
    const io::ImageF out =
        gpu ? gpu_backend("--gpu").composite(bg, obj, alpha, depth, q.camera, q.settings)
            : haze::composite(bg, obj, alpha, depth, q.camera, q.settings);
    check_finite(out);
    Result res;
    r.write_image(res, "output", out,
                  haze::haze_metadata("composite", q.air, q.camera, q.settings));
    res.record = image_result().record({"composite", bg.width, bg.height,
                                        q.settings.airlight_source_map != nullptr, gpu, 0, 0, 0.0,
                                        q.settings.min_transmission});
    return res;
  };
  return haze_operation(info);
}

// ---- sky mask -----------------------------------------------------------------------------------

struct SkyMaskResult {
  int width = 0, height = 0;
  long long sky_pixels = 0;
};

const ResultSchema<SkyMaskResult>& sky_mask_result() {
  using R = SkyMaskResult;
  static const ResultSchema<R> s = [] {
    ResultSchema<R> s;
    s.integer("width", "px", "the photo's width", &R::width)
        .integer("height", "px", "its height", &R::height)
        .integer("sky_pixels", "1", "pixels of the sky", &R::sky_pixels)
        .number(
            "sky_percent", "%", "their share of the photo",
            [](const R& r) {
              return 100.0 * static_cast<double>(r.sky_pixels) /
                     (static_cast<double>(r.width) * r.height);
            },
            1);
    return s;
  }();
  return s;
}

OperationInfo sky_mask_operation() {
  const auto& a = haze::AirlightOptions::schema();
  ParameterSpec sky = *a.find("sky");
  sky.default_value = Required{};
  OperationInfo info{
      .name = "haze sky-mask",
      .summary = "the sky of a photo as a mask",
      .description =
          "the sky of a photo by a marker-controlled watershed (the segmentation of "
          "Morales et al. 2017 eq. 12)",
      .parameters =
          concat({{sky},
                  image_schema(estimate::photo_image_options(Projection::fisheye, "sky-projection",
                                                             "--sky: the sky photo's layout"))
                      .specs(),
                  {output_file("output", "the mask: 8-bit PNG, 255 = sky", kPngFormat)}}),
      .result = sky_mask_result().fields(),
      .result_type = "estimate::SkyMask"};
  info.run = [](const Request& r, const ProgressSink&) {
    const auto air = r.bind(haze::AirlightOptions::schema());
    const io::ImageF photo = r.image("sky");
    const Camera cam = io::photo_camera(air.sky_image, photo.width, photo.height);
    const estimate::SkyMask mask = haze::segment_sky(photo, cam);
    Result res;
    r.write_png(res, "output", haze::mask_image(mask),
                {{"Software", fmt::format("skylight {}", kVersion)},
                 {"Comment", "sky mask (watershed, Morales 2017 eq. 12): 255 = sky"}});
    res.record =
        sky_mask_result().record({photo.width, photo.height, static_cast<long long>(mask.count)});
    return res;
  };
  return haze_operation(info, false);
}

}  // namespace

std::vector<OperationInfo> haze_operations() {
  return {
      coefficients_operation(),
      attenuation_operation(),
      cameras_operation(),
      image_operation(haze::HazeOperation::add, "add", "add haze to an image with depth (eq. 10)",
                      "haze added to an image with depth (eq. 10)"),
      image_operation(haze::HazeOperation::retarget, "retarget",
                      "re-target haze from T to T_t (eq. 26)",
                      "haze re-targeted from T to T_t (eq. 26)"),
      image_operation(haze::HazeOperation::remove, "remove", "remove haze (eq. 10 inverted)",
                      "haze removed (eq. 10 inverted)"),
      composite_operation(),
      sky_mask_operation()};
}

}  // namespace skylight::operations::detail
