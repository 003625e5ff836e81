#include "skylight/haze/request.h"
#include "skylight/io/camera_calibration.h"

#include <fmt/format.h>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/numbers.h"
#include "skylight/core/parameters.h"
#include "skylight/estimate/photo.h"
#include "skylight/io/image.h"
#include "skylight/models/sky_model.h"
#include "skylight/version.h"

namespace skylight::haze {
namespace {

// Clip planes of a pinhole image camera when the depth map holds metres (the pixels' directions do
// not depend on them) [m].
constexpr double kPinholeNearM = 1.0, kPinholeFarM = 1e4;

Mat4 to_mat4(const std::vector<double>& v) {
  Mat4 m{};
  for (std::size_t i = 0; i < 16; ++i) m[i] = v[i];
  return m;
}

ParameterSpec matrix_spec(const char* name, const char* help) {
  return {.name = name,
          .unit = "1",
          .kind = ParameterKind::numbers,
          .min = -1e30,
          .max = 1e30,
          .count = 16,
          .default_value = Absent{"no camera"},
          .description = help};
}

ParameterSpec angle_spec(const char* name, double lo, double hi, const char* help) {
  return {.name = name,
          .unit = "deg",
          .min = lo,
          .max = hi,
          .default_value = ParameterValue(0.0),
          .description = help};
}

}  // namespace

const ParameterSchema<Atmosphere>& atmosphere_schema() {
  static const ParameterSchema<Atmosphere> s = [] {
    ParameterSchema<Atmosphere> s;
    s.number(&Atmosphere::turbidity,
             {.name = "turbidity",
              .unit = "1",
              .min = 1.0,
              .max = 64.0,
              .default_value = Required{},
              .description = "turbidity T of the air (Morales 2017 eq. 5; 1 = pure air)"})
        .number(&Atmosphere::altitude_m,
                {.name = "altitude",
                 .unit = "m",
                 .min = -500.0,
                 .max = 20000.0,
                 .default_value = ParameterValue(0.0),
                 .description = "observer altitude h0 above sea level (horizontal paths at h0)"})
        .choice(
            &Atmosphere::variant,
            {.name = "variant",
             .kind = ParameterKind::text,
             .default_value = ParameterValue(std::string(to_string(ScatteringVariant::improved))),
             .description =
                 "scattering coefficients: improved (Morales 2017 eqs. 15, 18), Preetham's or "
                 "Zhao's (eqs. 3, 4)"},
            {{std::string(to_string(ScatteringVariant::improved)), ScatteringVariant::improved},
             {std::string(to_string(ScatteringVariant::preetham)), ScatteringVariant::preetham},
             {std::string(to_string(ScatteringVariant::zhao)), ScatteringVariant::zhao}});
    return s;
  }();
  return s;
}

const ParameterSchema<SensitivityOptions>& SensitivityOptions::schema() {
  static const ParameterSchema<SensitivityOptions> s = [] {
    ParameterSchema<SensitivityOptions> s;
    s.text(&SensitivityOptions::camera,
           {.name = "camera",
            .kind = ParameterKind::text,
            .default_value = Absent{"--camera-csv"},
            .description = "camera spectral sensitivity by name (skylight haze cameras)"})
        .text(&SensitivityOptions::camera_csv,
              {.name = "camera-csv",
               .kind = ParameterKind::text,
               .default_value = Absent{"--camera"},
               .description = "camera sensitivities: CSV 'nm,r,g,b'"});
    return s;
  }();
  return s;
}

CameraSensitivity SensitivityOptions::sensitivity() const {
  if (!camera_csv.empty()) return load_camera_csv(camera_csv);
  if (camera.empty())
    throw InvalidArgument(
        fmt::format("give {} NAME or {} FILE", spelled("camera"), spelled("camera-csv")));
  return find_camera(camera);
}

const ParameterSchema<ImageCameraOptions>& ImageCameraOptions::schema() {
  static const ParameterSchema<ImageCameraOptions> s = [] {
    using C = ImageCameraOptions;
    ParameterSchema<C> s;
    s.optional_number(
         &C::vfov_deg,
         {.name = "vfov",
          .unit = "deg",
          .min = 0.01,
          .max = 179.0,
          .default_value = Absent{"no camera"},
          .description = "image camera (pinhole): vertical field of view across the image; gives "
                         "every pixel its own airlight (--sky, --sky-model)"})
        .optional_number(
            &C::hfov_deg,
            {.name = "hfov",
             .unit = "deg",
             .min = 0.01,
             .max = 179.0,
             .default_value = Absent{"no camera"},
             .description = "image camera (pinhole): horizontal field of view (instead of --vfov)"})
        .optional_number(&C::heading_deg,
                         angle_spec("heading", -360.0, 360.0,
                                    "image camera: azimuth of the optical axis (north 0, east 90)"))
        .optional_number(&C::pitch_deg, angle_spec("pitch", -90.0, 90.0,
                                                   "image camera: elevation of the optical axis"))
        .optional_number(&C::roll_deg,
                         angle_spec("roll", -180.0, 180.0,
                                    "image camera: turn about the optical axis, clockwise as the "
                                    "camera sees it"))
        .numbers(&C::view_matrix,
                 matrix_spec("view-matrix",
                             "image camera: OpenGL model-view matrix M, 16 numbers row-major, "
                             "world frame East-North-Up (instead of --heading/--pitch/--roll)"))
        .numbers(&C::projection_matrix,
                 matrix_spec("projection-matrix",
                             "image camera: OpenGL projection matrix P, 16 numbers row-major "
                             "(instead of --vfov/--hfov)"));
    return s;
  }();
  return s;
}

bool ImageCameraOptions::given() const {
  return vfov_deg || hfov_deg || !projection_matrix.empty() || !view_matrix.empty() ||
         heading_deg || pitch_deg || roll_deg;
}

std::optional<ImagePositioning> ImageCameraOptions::positioning(int width, int height,
                                                                double near_m, double far_m) const {
  if (!given()) return std::nullopt;
  if (!vfov_deg && !hfov_deg && projection_matrix.empty())
    throw InvalidArgument(fmt::format("the image camera needs a field of view: give {}, {} or {}",
                                      spelled("vfov"), spelled("hfov"),
                                      spelled("projection-matrix")));
  const Mat4 view = view_matrix.empty()
                        ? haze::view_matrix(wrap_azimuth(deg_to_rad(heading_deg.value_or(0.0))),
                                            deg_to_rad(pitch_deg.value_or(0.0)),
                                            deg_to_rad(roll_deg.value_or(0.0)))
                        : to_mat4(view_matrix);
  const double aspect = static_cast<double>(width) / height;
  Mat4 projection{};
  if (!projection_matrix.empty()) {
    projection = to_mat4(projection_matrix);
  } else {
    const double fov_y =
        vfov_deg ? deg_to_rad(*vfov_deg) : vertical_fov(deg_to_rad(*hfov_deg), aspect);
    projection = perspective_matrix(fov_y, aspect, near_m, far_m);
  }
  return ImagePositioning(view, projection, width, height);
}

const ParameterSchema<CoefficientsOptions>& CoefficientsOptions::schema() {
  static const ParameterSchema<CoefficientsOptions> s = [] {
    ParameterSchema<CoefficientsOptions> s;
    s.number(&CoefficientsOptions::wavelength_nm, {.name = "wavelength",
                                                   .unit = "nm",
                                                   .min = 300.0,
                                                   .max = 1000.0,
                                                   .default_value = ParameterValue(550.0),
                                                   .description = "wavelength"});
    return s;
  }();
  return s;
}

const ParameterSchema<AttenuationOptions>& AttenuationOptions::schema() {
  static const ParameterSchema<AttenuationOptions> s = [] {
    ParameterSchema<AttenuationOptions> s;
    s.number(&AttenuationOptions::distance_m, {.name = "distance",
                                               .unit = "m",
                                               .min = 0.0,
                                               .max = 1e7,
                                               .default_value = Required{},
                                               .description = "path length s"});
    return s;
  }();
  return s;
}

std::string_view to_string(HorizonRegion region) {
  return region == HorizonRegion::watershed ? "watershed" : "band";
}

const ParameterSchema<AirlightOptions>& AirlightOptions::schema() {
  static const ParameterSchema<AirlightOptions> s = [] {
    using A = AirlightOptions;
    const auto& sun = sun_parameter_specs();
    ParameterSchema<A> s;
    s.numbers(&A::airlight,
              {.name = "airlight",
               .unit = "image units",
               .kind = ParameterKind::numbers,
               .min = 1e-30,
               .max = 1e30,
               .count = 3,
               .default_value = Absent{"from --sky-model"},
               .description = "constant airlight I^inf R,G,B (Morales 2017 eq. 10), > 0"})
        .text(&A::sky_model,
              {.name = "sky-model",
               .kind = ParameterKind::text,
               .default_value = Absent{"--airlight"},
               .description = "airlight from a spectral sky model with a turbidity at the "
                              "turbidity, seen through the camera (eq. 7); beyond the model's "
                              "spectrum the camera sees its last radiance (docs/HAZE.md)",
               .choices = airlight_models()})
        .text(&A::sky_photo,
              {.name = "sky",
               .kind = ParameterKind::text,
               .default_value = Absent{"--airlight"},
               .description = "airlight from a sky photo's horizon region (eqs. 12-13): linear "
                              ".exr, .hdr or .pfm"})
        .nested(&A::sky_image,
                image_schema(estimate::photo_image_options(Projection::fisheye, "sky-projection",
                                                           "--sky: the sky photo's layout")))
        .choice(&A::horizon_region,
                {.name = "horizon-region",
                 .kind = ParameterKind::text,
                 .default_value = ParameterValue(std::string("watershed")),
                 .description =
                     "--sky: the horizon region over the watershed sky mask (the band above the "
                     "skyline) or the fixed band above the horizon (docs/HAZE.md)"},
                {{"watershed", HorizonRegion::watershed}, {"band", HorizonRegion::band}})
        .text(&A::sky_mask,
              {.name = "sky-mask",
               .kind = ParameterKind::text,
               .default_value = Absent{"the watershed's"},
               .description = "--sky: its sky mask (.png, .pfm, .exr; nonzero = sky, e.g. from "
                              "`skylight haze sky-mask`) instead of the watershed"})
        .number(&A::sun_zenith_deg, sun[0])
        .number(&A::sun_azimuth_deg, sun[1])
        .optional_number(
            &A::view_elevation_deg,
            {.name = "view-elevation",
             .unit = "deg",
             .min = 0.0,
             .max = 90.0,
             .default_value = ParameterValue(0.0),
             .description = "--sky-model, --sky without an image camera: elevation of the sky seen "
                            "behind the scene"})
        .optional_number(
            &A::view_azimuth_deg,
            {.name = "view-azimuth",
             .unit = "deg",
             .min = -360.0,
             .max = 360.0,
             .default_value = ParameterValue(0.0),
             .description = "--sky-model without an image camera: azimuth of that direction "
                            "(north 0, east 90)"});
    return s;
  }();
  return s;
}

AirlightSource::AirlightSource(AirlightOptions options) : options_(std::move(options)) {}

PhotoAirlight AirlightSource::photo_horizon(double t, double theta) const {
  const AirlightOptions& o = options_;
  if (!photo_) {
    const io::ImageF image = io::read_image(o.sky_photo);
    const Camera cam = io::photo_camera(o.sky_image, image.width, image.height);
    HorizonSettings h;
    h.region = o.horizon_region;
    if (h.region == HorizonRegion::band && !o.sky_mask.empty())
      throw InvalidArgument(
          fmt::format("{} goes with {} watershed", spelled("sky-mask"), spelled("horizon-region")));
    estimate::SkyMask mask;
    if (!o.sky_mask.empty()) {
      mask = mask_from_image(estimate::load_mask(o.sky_mask), cam);
      h.mask = &mask;
    }
    photo_ = photo_airlight(image, cam, t, theta, h);
  }
  PhotoAirlight out = *photo_;
  const double z = zeta(t, theta, out.theta_prime);
  for (std::size_t c = 0; c < 3; ++c) out.airlight[c] = out.horizon[c] * z;
  return out;
}

std::vector<std::string> airlight_models() {
  std::vector<std::string> names;
  for (const ModelInfo& m : model_registry())
    if (m.spectral && m.find_parameter("turbidity") != nullptr) names.push_back(m.name);
  return names;
}

std::unique_ptr<SkyModel> AirlightSource::model_at(double t) const {
  const ModelInfo* info = &require_model(options_.sky_model, "sky-model");
  SkyParameters p;
  p.sun = sun_from_degrees(options_.sun_zenith_deg, options_.sun_azimuth_deg);
  p.values = info->example;
  if (!info->spectral || info->find_parameter("turbidity") == nullptr)
    throw InvalidArgument(
        fmt::format("{} '{}' is not a spectral model with a turbidity (those are: {})",
                    spelled("sky-model"), info->name, fmt::join(airlight_models(), ", ")));
  p.values.set("turbidity", t);
  return make_sky_model(info->name, p);
}

std::shared_ptr<const AirlightMap> AirlightSource::per_pixel(double t,
                                                             const CameraSensitivity& camera,
                                                             const ImagePositioning& image) const {
  if (options_.view_elevation_deg || options_.view_azimuth_deg)
    throw InvalidArgument(
        fmt::format("{} and {} are for one airlight per image; with an image camera every "
                    "pixel sees its own direction",
                    spelled("view-elevation"), spelled("view-azimuth")));
  if (!options_.airlight.empty()) return nullptr;
  if (!options_.sky_photo.empty()) return photo_airlight_map(image, photo_horizon(t, kPi / 2), t);
  const AirlightTable table(*model_at(t), camera);
  return sky_model_airlight_map(image, table);
}

Rgb3 AirlightSource::at(double t, const CameraSensitivity& camera) const {
  const AirlightOptions& o = options_;
  if (!o.airlight.empty()) return {o.airlight[0], o.airlight[1], o.airlight[2]};
  const double theta = deg_to_rad(90.0 - o.view_elevation_deg.value_or(0.0));
  if (!o.sky_photo.empty()) return photo_horizon(t, theta).airlight;
  if (o.sky_model.empty())
    throw InvalidArgument(fmt::format("give {} R,G,B, {} PHOTO or {} NAME", spelled("airlight"),
                                      spelled("sky"), spelled("sky-model")));
  const auto model = model_at(t);
  const Vec3 view =
      direction_from_angles(theta, wrap_azimuth(deg_to_rad(o.view_azimuth_deg.value_or(0.0))));
  return sky_model_airlight(*model, view, camera);
}

const ParameterSchema<HazeOptions>& HazeOptions::schema() {
  static const ParameterSchema<HazeOptions> s = [] {
    using H = HazeOptions;
    ParameterSchema<H> s;
    s.optional_number(
         &H::target_turbidity,
         {.name = "target-turbidity",
          .unit = "1",
          .min = 1.0,
          .max = 64.0,
          .default_value = Absent{"required by retarget, refused by the other operations"},
          .description = "turbidity T_t to re-target to (eq. 26)"})
        .optional_number(&H::near_m, {.name = "near",
                                      .unit = "m",
                                      .min = 1e-6,
                                      .max = 1e9,
                                      .default_value = Absent{"the depth map holds metres"},
                                      .description = "near plane of a normalised depth map"})
        .optional_number(&H::far_m, {.name = "far",
                                     .unit = "m",
                                     .min = 1e-6,
                                     .max = 1e9,
                                     .default_value = Absent{"the depth map holds metres"},
                                     .description = "far plane of a normalised depth map"})
        .number(
            &H::min_transmission,
            {.name = "min-transmission",
             .unit = "1",
             .min = 1e-6,
             .max = 1.0,
             .default_value = ParameterValue(kDefaultMinTransmission),
             .description =
                 "remove/retarget: Gamma_s is taken as at least this (bounds the amplification)"});
    return s;
  }();
  return s;
}

HazeSettings haze_settings(HazeOperation operation, const Atmosphere& air, const HazeOptions& o,
                           const CameraSensitivity& camera, const AirlightSource& airlight,
                           const ImageCameraOptions& image_camera, int width, int height) {
  HazeSettings s;
  s.operation = operation;
  s.source = air;
  validate(s.source);
  s.min_transmission = o.min_transmission;
  s.airlight_source = airlight.at(air.turbidity, camera);
  if (operation == HazeOperation::retarget) {
    if (!o.target_turbidity)
      throw InvalidArgument("haze retarget needs " + spelled("target-turbidity"));
    s.target_turbidity = o.target_turbidity;
    s.airlight_target = airlight.at(*o.target_turbidity, camera);
  } else if (o.target_turbidity) {
    throw InvalidArgument(spelled("target-turbidity") + " is for haze retarget only");
  }
  // With an image camera, --sky and --sky-model give every pixel the airlight of its own direction
  // (Morales 2017 §6.2: eqs. 20-22, then eqs. 12-13 or the model); --airlight stays constant.
  const std::optional<ImagePositioning> image = image_camera.positioning(
      width, height, o.near_m.value_or(kPinholeNearM), o.far_m.value_or(kPinholeFarM));
  if (image) {
    s.airlight_source_map = airlight.per_pixel(air.turbidity, camera, *image);
    if (s.airlight_source_map && s.target_turbidity)
      s.airlight_target_map = airlight.per_pixel(*s.target_turbidity, camera, *image);
  }
  return s;
}

ImageHazeRequest image_haze_request(HazeOperation operation, const ParameterValues& given,
                                    int width, int height) {
  const auto bound = [&](const auto& schema, auto value) {
    schema.bind(given.only(schema.specs()), value, "haze");
    return value;
  };
  ImageHazeRequest r;
  r.air = bound(atmosphere_schema(), Atmosphere{});
  validate(r.air);
  r.camera = bound(SensitivityOptions::schema(), SensitivityOptions{}).sensitivity();
  r.options = bound(HazeOptions::schema(), HazeOptions{});
  r.settings =
      haze_settings(operation, r.air, r.options, r.camera,
                    AirlightSource(bound(AirlightOptions::schema(), AirlightOptions{})),
                    bound(ImageCameraOptions::schema(), ImageCameraOptions{}), width, height);
  return r;
}

io::ImageF coverage_from_depth(const io::ImageF& depth) {
  io::ImageF alpha(depth.width, depth.height, 1);
  for (std::size_t i = 0; i < alpha.data.size(); ++i)
    alpha.data[i] = depth.data[i] > 0.0f ? 1.0f : 0.0f;
  return alpha;
}

std::vector<std::pair<std::string, std::string>> haze_metadata(std::string_view operation,
                                                               const Atmosphere& air,
                                                               const CameraSensitivity& camera,
                                                               const HazeSettings& s) {
  std::vector<std::pair<std::string, std::string>> md{
      {"skylight:version", kVersion},
      {"skylight:haze_operation", std::string(operation)},
      {"skylight:camera", camera.name},
      {"skylight:scattering_variant", std::string(to_string(air.variant))},
      {"skylight:turbidity", fmt::format("{}", air.turbidity)},
      {"skylight:altitude_m", fmt::format("{}", air.altitude_m)},
      {"skylight:airlight", s.airlight_source_map
                                ? std::string("per pixel")
                                : fmt::format("{},{},{}", s.airlight_source[0],
                                              s.airlight_source[1], s.airlight_source[2])}};
  if (s.target_turbidity)
    md.emplace_back("skylight:target_turbidity", fmt::format("{}", *s.target_turbidity));
  return md;
}

}  // namespace skylight::haze
