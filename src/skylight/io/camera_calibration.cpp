#include "skylight/io/camera_calibration.h"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/numbers.h"
#include "skylight/io/file.h"

namespace skylight::io {
namespace {

using Json = nlohmann::json;

// The keys a calibration may hold (docs/CONVENTIONS.md); any other is refused (a typo would
// otherwise be ignored).
constexpr const char* kKeys[] = {"projection",      "lens",       "fov_deg",
                                 "centre_px",       "radius_px",  "mirrored",
                                 "north_angle_deg", "image_size", "comment"};

double number(const Json& j, const char* key, std::string_view name) {
  const Json& v = j.at(key);
  if (!v.is_number() || !std::isfinite(v.get<double>()))
    throw InvalidArgument(fmt::format("{}: \"{}\" must be a finite number", name, key));
  return v.get<double>();
}

}  // namespace

CameraCalibration parse_camera_calibration(std::string_view json, std::string_view name_in) {
  const std::string name = excerpt(name_in);
  Json j;
  try {
    j = Json::parse(json);
  } catch (const Json::exception& e) {  // parse_error, and out_of_range for 1e400
    throw InvalidArgument(fmt::format("{}: not JSON ({})", name, excerpt(e.what(), 120)));
  }
  if (!j.is_object()) throw InvalidArgument(fmt::format("{}: not a JSON object", name));
  for (const auto& [key, value] : j.items())
    if (std::find(std::begin(kKeys), std::end(kKeys), key) == std::end(kKeys))
      throw InvalidArgument(fmt::format("{}: unknown key \"{}\"", name, excerpt(key)));
  CameraCalibration c;
  c.name = name;
  if (!j.contains("projection") || !j["projection"].is_string())
    throw InvalidArgument(
        fmt::format("{}: \"projection\" (\"fisheye\" or \"equirect\") is required", name));
  const auto projection = parse_projection(j["projection"].get<std::string>());
  if (projection != Projection::fisheye && projection != Projection::equirect)
    throw InvalidArgument(
        fmt::format("{}: \"projection\" must be \"fisheye\" or \"equirect\"", name));
  c.projection = *projection;
  const bool fisheye = c.projection == Projection::fisheye;
  for (const char* key :
       {"lens", "fov_deg", "centre_px", "radius_px", "mirrored", "north_angle_deg"})
    if (!fisheye && j.contains(key))
      throw InvalidArgument(
          fmt::format("{}: \"{}\" is a fisheye's; the projection is equirect", name, key));
  if (j.contains("lens")) {
    const auto lens =
        j["lens"].is_string() ? parse_fisheye_lens(j["lens"].get<std::string>()) : std::nullopt;
    if (!lens)
      throw InvalidArgument(fmt::format(
          "{}: \"lens\" must be equidistant, equisolid, orthographic or stereographic", name));
    c.fisheye.lens = *lens;
  }
  if (j.contains("fov_deg")) c.fisheye.fov = deg_to_rad(number(j, "fov_deg", name));
  if (j.contains("north_angle_deg"))
    c.fisheye.north_angle = deg_to_rad(number(j, "north_angle_deg", name));
  if (j.contains("radius_px")) c.fisheye.radius = number(j, "radius_px", name);
  if (j.contains("centre_px")) {
    const Json& v = j["centre_px"];
    if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
      throw InvalidArgument(fmt::format("{}: \"centre_px\" must be [column, row]", name));
    c.fisheye.centre = std::array<double, 2>{v[0].get<double>(), v[1].get<double>()};
  }
  if (j.contains("mirrored")) {
    if (!j["mirrored"].is_boolean())
      throw InvalidArgument(fmt::format("{}: \"mirrored\" must be true or false", name));
    c.fisheye.mirrored = j["mirrored"].get<bool>();
  }
  if (j.contains("image_size")) {
    const Json& v = j["image_size"];
    if (!v.is_array() || v.size() != 2 || !v[0].is_number_integer() || !v[1].is_number_integer() ||
        v[0].get<long long>() < 1 || v[1].get<long long>() < 1 ||
        v[0].get<long long>() > kMaxImageSide || v[1].get<long long>() > kMaxImageSide)
      throw InvalidArgument(fmt::format(
          "{}: \"image_size\" must be [width, height] in pixels, 1 to {}", name, kMaxImageSide));
    c.image_size = std::array<int, 2>{v[0].get<int>(), v[1].get<int>()};
  }
  // The layout's own checks (fov within the lens's limits, a positive radius), named.
  try {
    Camera probe;
    probe.projection = c.projection;
    probe.width = probe.height = 2;
    probe.fisheye = c.fisheye;
    validate(probe);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(fmt::format("{}: {}", name, e.what()));
  }
  return c;
}

CameraCalibration read_camera_calibration(const std::filesystem::path& path) {
  return parse_camera_calibration(read_text_file(path), shown_path(path));
}

Camera CameraCalibration::camera(int width, int height,
                                 std::optional<double> focal_length_px) const {
  if (image_size && ((*image_size)[0] != width || (*image_size)[1] != height))
    throw InvalidArgument(fmt::format("{} is for {} x {} photos, not {} x {}", name,
                                      (*image_size)[0], (*image_size)[1], width, height));
  FisheyeLayout layout = fisheye;
  if (projection == Projection::fisheye && !layout.radius && focal_length_px) {
    // The lens maps zenith angle theta to f g(theta) pixels from the centre.
    if (const auto g = fisheye_lens_mapping(layout.lens, 0.5 * layout.fov))
      layout.radius = *focal_length_px * *g;
  }
  try {
    return image_camera(projection, layout, width, height);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(fmt::format("{}: {}", name, e.what()));
  }
}

Camera photo_camera(const ImageOptions& options, int width, int height,
                    std::optional<double> focal_length_px) {
  if (options.calibration.empty()) return options.camera(width, height);
  return read_camera_calibration(options.calibration).camera(width, height, focal_length_px);
}

}  // namespace skylight::io
