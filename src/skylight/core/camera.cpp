#include "skylight/core/camera.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "skylight/core/error.h"

namespace skylight {
namespace {

// Pinhole camera: d = normalize(f + x tan(fov/2) right + y tan(fov/2) up), x in [-w/h, w/h],
// y in [-1, 1] (image up), right = f x zenith (f x north when f is vertical), up = right x f.
Vec3 pinhole_direction(double u, double v, int width, int height, const PinholeLayout& c) {
  const Vec3 f = direction_from_angles(c.look_zenith, c.look_azimuth);
  Vec3 right = cross(f, Vec3{0, 0, 1});
  if (dot(right, right) < 1e-12) right = cross(f, Vec3{0, 1, 0});
  right = normalize(right);
  const Vec3 up = cross(right, f);
  const double t = std::tan(0.5 * c.vertical_fov);
  const double x = (2.0 * u / height - static_cast<double>(width) / height) * t;
  const double y = (1.0 - 2.0 * v / height) * t;
  return normalize(f + x * right + y * up);
}

void validate_fisheye(const FisheyeLayout& f) {
  const double fov_deg = rad_to_deg(f.fov);
  const double max_deg = f.lens == FisheyeLens::orthographic ? 180.0 : 360.0;
  if (!(fov_deg > 0.0 && fov_deg <= max_deg) ||
      (f.lens == FisheyeLens::stereographic && fov_deg >= 360.0))
    throw InvalidArgument(fmt::format("fov = {} deg is outside (0, {}{} for the {} lens", fov_deg,
                                      max_deg, f.lens == FisheyeLens::stereographic ? ")" : "]",
                                      to_string(f.lens)));
  if (!std::isfinite(f.north_angle))
    throw InvalidArgument(fmt::format("north-angle = {} is not finite", f.north_angle));
  if (f.radius && !(std::isfinite(*f.radius) && *f.radius > 0.0))
    throw InvalidArgument(
        fmt::format("the image circle's radius {} px is not positive", *f.radius));
  if (f.centre && !(std::isfinite((*f.centre)[0]) && std::isfinite((*f.centre)[1])))
    throw InvalidArgument("the image circle's centre is not finite");
}

}  // namespace

std::optional<Projection> parse_projection(std::string_view name) {
  if (name == "equirect") return Projection::equirect;
  if (name == "hemisphere") return Projection::hemisphere;
  if (name == "fisheye") return Projection::fisheye;
  if (name == "cubemap") return Projection::cubemap;
  if (name == "camera") return Projection::camera;
  return std::nullopt;
}

std::string_view to_string(Projection p) {
  switch (p) {
    case Projection::equirect:
      return "equirect";
    case Projection::hemisphere:
      return "hemisphere";
    case Projection::fisheye:
      return "fisheye";
    case Projection::cubemap:
      return "cubemap";
    case Projection::camera:
      return "camera";
  }
  return "equirect";
}

std::optional<Vec3> Camera::direction(double u, double v) const {
  switch (projection) {
    case Projection::equirect:
      if (u < 0.0 || u > width || v < 0.0 || v > height) return std::nullopt;
      return equirect_direction(u, v, width, height);
    case Projection::hemisphere:
      return hemisphere_direction(u, v, width, height);
    case Projection::fisheye:
      return fisheye_direction(u, v, width, height, fisheye);
    case Projection::cubemap:
      return cubemap_direction(u, v, width, height);
    case Projection::camera:
      return pinhole_direction(u, v, width, height, pinhole);
  }
  return std::nullopt;
}

std::optional<std::array<double, 2>> Camera::pixel(Vec3 d) const {
  if (projection == Projection::fisheye) return fisheye_pixel(d, width, height, fisheye);
  if (projection != Projection::equirect) return std::nullopt;
  // Inverse of equirect_direction: theta = pi row / height, phi = 2 pi col / width
  // (docs/CONVENTIONS.md, pixel centres at +0.5).
  const ZenithAzimuth za = angles_from_direction(d);
  return std::array<double, 2>{za.azimuth / (2.0 * kPi) * width, za.zenith / kPi * height};
}

void validate(const Camera& s) {
  if (s.width < 1 || s.width > kMaxImageSide)
    throw InvalidArgument(fmt::format("width = {} is outside [1, {}]", s.width, kMaxImageSide));
  if (s.height < 1 || s.height > kMaxImageSide)
    throw InvalidArgument(fmt::format("height = {} is outside [1, {}]", s.height, kMaxImageSide));
  if (s.projection == Projection::cubemap && s.width != 6 * s.height)
    throw InvalidArgument(fmt::format(
        "cubemap needs width = 6 x height (six square faces); got {} x {}", s.width, s.height));
  if (s.projection == Projection::camera) {
    const PinholeLayout& c = s.pinhole;
    if (!(c.vertical_fov > 0.0 && c.vertical_fov < kPi))
      throw InvalidArgument(fmt::format("fov = {} deg is outside (0, 180) for the camera",
                                        rad_to_deg(c.vertical_fov)));
    if (!(c.look_zenith >= 0.0 && c.look_zenith <= kPi) || !std::isfinite(c.look_azimuth))
      throw InvalidArgument(
          fmt::format("camera look direction (zenith {} deg, azimuth {} deg) is not a direction",
                      rad_to_deg(c.look_zenith), rad_to_deg(c.look_azimuth)));
  }
  if (s.projection == Projection::fisheye) validate_fisheye(s.fisheye);
}

namespace {

std::string projection_help(Projection p) {
  switch (p) {
    case Projection::equirect:
      return "equirect (the full sphere)";
    case Projection::hemisphere:
      return "hemisphere (the upper half)";
    case Projection::fisheye:
      return "fisheye";
    case Projection::cubemap:
      return "cubemap (six faces in a strip, width = 6 x height)";
    case Projection::camera:
      return "camera (a pinhole, e.g. of the planet from orbit)";
  }
  return {};
}

}  // namespace

Camera ImageOptions::camera() const {
  const int w = width ? *width : projection == Projection::cubemap ? 6 * height : default_width;
  return camera(w, height);
}

Camera ImageOptions::camera(int w, int h) const {
  SKYLIGHT_CHECK(calibration.empty(), "a calibrated photo's camera is io::photo_camera's");
  Camera c;
  c.projection = projection;
  c.width = w;
  c.height = h;
  c.fisheye = {lens, deg_to_rad(fov_deg.value_or(kFisheyeFovDeg)), deg_to_rad(north_angle_deg)};
  c.pinhole.look_zenith = deg_to_rad(90.0 - look_elevation_deg);
  c.pinhole.look_azimuth = wrap_azimuth(deg_to_rad(look_azimuth_deg));
  c.pinhole.vertical_fov = deg_to_rad(fov_deg.value_or(kPinholeFovDeg));
  validate(c);
  return c;
}

std::vector<std::string> ImageOptions::unread(const ParameterValues& given) const {
  if (!calibration.empty()) {
    std::vector<std::string> out;
    for (const std::string& name :
         {projection_flag, std::string("lens"), std::string("fov"), std::string("north-angle")})
      if (given.has(name)) out.push_back(name);
    return out;
  }
  const bool fisheye = projection == Projection::fisheye;
  const bool pinhole = projection == Projection::camera;
  const std::pair<const char*, bool> options[] = {{"lens", fisheye},
                                                  {"north-angle", fisheye},
                                                  {"fov", fisheye || pinhole},
                                                  {"look-elevation", pinhole},
                                                  {"look-azimuth", pinhole}};
  std::vector<std::string> out;
  for (const auto& [name, used] : options)
    if (!used && given.has(name)) out.emplace_back(name);
  return out;
}

std::vector<std::pair<std::string, std::string>> ImageOptions::metadata() const {
  std::vector<std::pair<std::string, std::string>> md{
      {"skylight:projection", std::string(to_string(projection))}};
  if (projection == Projection::camera) {
    md.emplace_back("skylight:fov_deg", fmt::format("{}", fov_deg.value_or(kPinholeFovDeg)));
    md.emplace_back("skylight:look_elevation_deg", fmt::format("{}", look_elevation_deg));
    md.emplace_back("skylight:look_azimuth_deg", fmt::format("{}", look_azimuth_deg));
  }
  if (projection == Projection::fisheye) {
    md.emplace_back("skylight:lens", std::string(to_string(lens)));
    md.emplace_back("skylight:fov_deg", fmt::format("{}", fov_deg.value_or(kFisheyeFovDeg)));
    md.emplace_back("skylight:north_angle_deg", fmt::format("{}", north_angle_deg));
  }
  return md;
}

ParameterSchema<ImageOptions> image_schema(const ImageSchemaOptions& o) {
  using P = ImageOptions;
  const auto takes = [&](Projection p) {
    return std::find(o.projections.begin(), o.projections.end(), p) != o.projections.end();
  };
  ParameterSchema<P> s;
  std::vector<std::pair<std::string, Projection>> names;
  std::string list;
  for (Projection p : o.projections) {
    names.emplace_back(std::string(to_string(p)), p);
    list += (list.empty() ? "" : ", ") + projection_help(p);
  }
  s.choice(
      &P::projection,
      {.name = o.projection_flag,
       .kind = ParameterKind::text,
       .default_value = ParameterValue(std::string(to_string(o.default_projection))),
       .description = (o.description.empty() ? std::string("the image's layout") : o.description) +
                      ": " + list},
      names);
  if (o.size) {
    s.optional_integer(
        &P::width, {.name = "width",
                    .unit = "px",
                    .kind = ParameterKind::integer,
                    .min = 1,
                    .max = static_cast<double>(kMaxImageSide),
                    .default_value = ParameterValue(static_cast<double>(o.width)),
                    .description = takes(Projection::cubemap)
                                       ? "image width (cubemap: must be 6 x height, which is its "
                                         "default)"
                                       : "image width"});
    s.integer(&P::height, {.name = "height",
                           .unit = "px",
                           .kind = ParameterKind::integer,
                           .min = 1,
                           .max = static_cast<double>(kMaxImageSide),
                           .default_value = ParameterValue(static_cast<double>(o.height)),
                           .description = "image height"});
  }
  const bool pinhole = takes(Projection::camera);
  if (takes(Projection::fisheye)) {
    s.choice(&P::lens,
             {.name = "lens",
              .kind = ParameterKind::text,
              .default_value = ParameterValue(std::string("equidistant")),
              .description = "fisheye lens"},
             {{"equidistant", FisheyeLens::equidistant},
              {"equisolid", FisheyeLens::equisolid},
              {"orthographic", FisheyeLens::orthographic},
              {"stereographic", FisheyeLens::stereographic}});
    s.optional_number(
        &P::fov_deg,
        {.name = "fov",
         .unit = "deg",
         .min = 1e-6,
         .max = 360.0,
         .default_value = Absent{pinhole ? fmt::format("{} (fisheye), {} (camera)", kFisheyeFovDeg,
                                                       kPinholeFovDeg)
                                         : fmt::format("{}", kFisheyeFovDeg)},
         .description =
             pinhole ? "fisheye: field of view across the image circle: (0, 360], orthographic (0, "
                       "180], stereographic (0, 360); camera: vertical field of view, (0, 180)"
                     : "fisheye: field of view across the image circle"});
    s.number(&P::north_angle_deg,
             {.name = "north-angle",
              .unit = "deg",
              .min = -360.0,
              .max = 360.0,
              .default_value = ParameterValue(0.0),
              .description = "fisheye: north drawn this many deg counter-clockwise from image up"});
  }
  if (!o.size)
    s.text(&P::calibration,
           {.name = o.calibration_flag(),
            .kind = ParameterKind::text,
            .default_value = Absent{"the projection options"},
            .description = "camera calibration file (JSON: projection, lens, fov_deg, centre_px, "
                           "radius_px, mirrored, north_angle_deg, image_size; "
                           "docs/CONVENTIONS.md): the photos' layout instead of the projection "
                           "options"});
  if (pinhole) {
    s.number(&P::look_elevation_deg, {.name = "look-elevation",
                                      .unit = "deg",
                                      .min = -90.0,
                                      .max = 90.0,
                                      .default_value = ParameterValue(0.0),
                                      .description = "camera: elevation of the view centre"});
    s.number(&P::look_azimuth_deg,
             {.name = "look-azimuth",
              .unit = "deg",
              .min = -360.0,
              .max = 360.0,
              .default_value = ParameterValue(0.0),
              .description = "camera: azimuth of the view centre from north towards east"});
  }
  return s;
}

std::string ImageSchemaOptions::calibration_flag() const {
  std::string f = projection_flag;
  if (const auto at = f.find("projection"); at != std::string::npos)
    f.replace(at, std::string_view("projection").size(), "calibration");
  return f;
}

Camera image_camera(Projection projection, const FisheyeLayout& layout, int width, int height) {
  Camera camera;
  camera.projection = projection;
  camera.width = width;
  camera.height = height;
  camera.fisheye = layout;
  validate(camera);
  return camera;
}

}  // namespace skylight
