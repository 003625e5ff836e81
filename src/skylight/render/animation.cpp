#include "skylight/render/animation.h"

#include <fmt/format.h>

#include <cmath>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/numbers.h"
#include "skylight/core/parameters.h"
#include "skylight/models/sky_model.h"
#include "skylight/sun/spa.h"
#include "skylight/sun/time.h"

namespace skylight::render {

ImageSchemaOptions AnimationOptions::image_options() {
  ImageSchemaOptions o;
  o.projections = {Projection::equirect, Projection::hemisphere, Projection::fisheye};
  return o;
}

const ParameterSchema<AnimationOptions>& AnimationOptions::schema() {
  static const ParameterSchema<AnimationOptions> s = [] {
    using A = AnimationOptions;
    ParameterSchema<A> s;
    s.numbers(&A::from, {.name = "from",
                         .unit = "deg",
                         .kind = ParameterKind::numbers,
                         .min = -360.0,
                         .max = 360.0,
                         .count = 2,
                         .default_value = Absent{"--from-time"},
                         .description = "the first frame's sun: zenith,azimuth"})
        .numbers(&A::to, {.name = "to",
                          .unit = "deg",
                          .kind = ParameterKind::numbers,
                          .min = -360.0,
                          .max = 360.0,
                          .count = 2,
                          .default_value = Absent{"--to-time"},
                          .description = "the last frame's sun: zenith,azimuth"})
        .text(&A::from_time,
              {.name = "from-time",
               .kind = ParameterKind::text,
               .default_value = Absent{"--from"},
               .description = "the first frame's time, ISO 8601 with UTC offset (the sun by the "
                              "SPA)"})
        .text(&A::to_time, {.name = "to-time",
                            .kind = ParameterKind::text,
                            .default_value = Absent{"--to"},
                            .description = "the last frame's time (times interpolated linearly)"})
        .optional_number(&A::lat_deg, sun::spa_parameter_spec("lat", "needed with --from-time"))
        .optional_number(&A::lon_deg, sun::spa_parameter_spec("lon", "needed with --from-time"))
        .integer(&A::frames, {.name = "frames",
                              .unit = "1",
                              .kind = ParameterKind::integer,
                              .min = 1,
                              .max = 100000,
                              .default_value = ParameterValue(static_cast<double>(A{}.frames)),
                              .description = "number of frames"})
        .nested(&A::image, image_schema(image_options()));
    return s;
  }();
  return s;
}

void AnimationOptions::validate() const {
  const bool by_time = !from_time.empty() || !to_time.empty();
  if (by_time) {
    if (from_time.empty() || to_time.empty() || !from.empty() || !to.empty())
      throw InvalidArgument(fmt::format("give {} and {}, or {} and {}", spelled("from-time"),
                                        spelled("to-time"), spelled("from"), spelled("to")));
    if (!lat_deg || !lon_deg)
      throw InvalidArgument(fmt::format("{}/{} need {} and {}", spelled("from-time"),
                                        spelled("to-time"), spelled("lat"), spelled("lon")));
  } else if (from.empty() || to.empty()) {
    throw InvalidArgument(fmt::format("give {} and {} (sun zenith,azimuth in deg), or {} and {}",
                                      spelled("from"), spelled("to"), spelled("from-time"),
                                      spelled("to-time")));
  }
}

SunPosition AnimationOptions::frame_sun(int k) const {
  const double u = frames > 1 ? static_cast<double>(k) / (frames - 1) : 0.0;
  if (!from_time.empty()) {
    const sun::DateTime t0 = sun::parse_iso8601(from_time);
    const sun::DateTime t1 = sun::parse_iso8601(to_time);
    const double jd0 = sun::julian_day(t0), jd1 = sun::julian_day(t1);
    sun::SpaInput in;
    in.time = sun::date_time_from_julian_day(jd0 + u * (jd1 - jd0), t0.utc_offset_minutes, 3);
    in.latitude = deg_to_rad(*lat_deg);
    in.longitude = deg_to_rad(*lon_deg);
    const sun::SpaResult r = sun::solar_position(in);
    return {r.zenith, r.azimuth};
  }
  const double da = std::remainder(to[1] - from[1], 360.0);  // the short way round
  const double zenith = from[0] + u * (to[0] - from[0]);
  return sun_from_degrees(zenith, from[1] + u * da);
}

std::string frame_path(const std::string& pattern, int frame, int frames) {
  const std::size_t a = pattern.find('#');
  if (a == std::string::npos)
    throw InvalidArgument(
        fmt::format("{} '{}': the pattern needs a run of '#' for the frame number",
                    spelled("output"), excerpt(pattern)));
  const std::size_t b = pattern.find_first_not_of('#', a);
  const std::size_t run = (b == std::string::npos ? pattern.size() : b) - a;
  const std::size_t digits = std::max(run, fmt::format("{}", frames - 1).size());
  return pattern.substr(0, a) + fmt::format("{:0{}}", frame, digits) +
         (b == std::string::npos ? std::string() : pattern.substr(b));
}

}  // namespace skylight::render
