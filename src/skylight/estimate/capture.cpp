#include "skylight/estimate/capture.h"

#include <fmt/format.h>

#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/sun/time.h"

namespace skylight::estimate {

const ParameterSchema<CaptureOptions>& CaptureOptions::schema() {
  static const ParameterSchema<CaptureOptions> s = [] {
    ParameterSchema<CaptureOptions> s;
    s.text(&CaptureOptions::exif,
           {.name = "exif",
            .kind = ParameterKind::text,
            .default_value = Absent{"none"},
            .description = "the capture's JPEG, TIFF or DNG: its EXIF time and GPS place give the "
                           "sun (SPA; --lat/--lon override the place), its focal length a "
                           "calibrated fisheye's radius"})
        .text(&CaptureOptions::utc_offset,
              {.name = "utc-offset",
               .kind = ParameterKind::text,
               .default_value = Absent{"the EXIF's OffsetTimeOriginal"},
               .description = "UTC offset of the EXIF time, +HH:MM or -HH:MM (cameras before "
                              "EXIF 2.31 write none)"});
    return s;
  }();
  return s;
}

Capture read_capture(const CaptureOptions& options, int photo_width) {
  Capture c;
  c.exif = io::read_exif(options.exif);
  if (c.exif.focal_length_px) {
    c.focal_length_px = *c.exif.focal_length_px;
    if (c.exif.pixel_width)
      *c.focal_length_px *= static_cast<double>(photo_width) / *c.exif.pixel_width;
  }
  return c;
}

sun::SpaInput capture_solar_input(const Capture& capture, const CaptureOptions& options,
                                  const ParameterValues& given) {
  const std::optional<std::string> offset =
      options.utc_offset.empty() ? std::nullopt : std::optional<std::string>(options.utc_offset);
  sun::SpaInput in;
  in.time = sun::parse_iso8601(capture.exif.time_iso8601(offset, options.exif));
  ParameterValues place = given.only(sun::spa_parameter_specs());
  const auto from_gps = [&](const char* name, const std::optional<double>& value) {
    if (!place.has(name) && value) place.set(name, *value);
  };
  from_gps("lat", capture.exif.latitude_deg);
  from_gps("lon", capture.exif.longitude_deg);
  from_gps("elevation", capture.exif.altitude_m);
  if (!place.has("lat") || !place.has("lon"))
    throw InvalidArgument(fmt::format("'{}' has a time but no GPS position: give {} and {}",
                                      excerpt(options.exif), spelled("lat"), spelled("lon")));
  sun::spa_input_schema().bind(place, in, spelled("exif"));
  sun::validate(in);
  return in;
}

}  // namespace skylight::estimate
