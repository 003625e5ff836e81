#include "skylight/daylight/daylight.h"

namespace skylight::daylight {

const ParameterSchema<DaylightRequest>& DaylightRequest::schema() {
  static const auto s = [] {
    ParameterSchema<DaylightRequest> s;
    s.nested(&DaylightRequest::sky, PerezParameters::irradiance_schema());
    s.text(&DaylightRequest::epw,
           {.name = "epw",
            .default_value = Absent{"one sky from --dni/--dhi (or their illuminances)"},
            .description = "EnergyPlus weather file: write the annual sky matrix of its hours "
                           "with the sun up (-o FILE.csv or FILE.npy)"});
    s.nested(&DaylightRequest::matrix, MatrixSettings::schema());
    return s;
  }();
  return s;
}

const std::vector<std::string>& DaylightRequest::one_sky_only() {
  static const std::vector<std::string> names = {
      "dni",         "dhi",       "dni-illuminance",   "dhi-illuminance",
      "day-of-year", "dew-point", "precipitable-water"};
  return names;
}

const std::vector<std::string>& DaylightRequest::matrix_only() {
  static const std::vector<std::string> names = {"patches",       "sun-patches", "hours",
                                                 "ground-albedo", "quantity",    "channels"};
  return names;
}

}  // namespace skylight::daylight
