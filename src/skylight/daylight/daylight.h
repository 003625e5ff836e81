// `skylight daylight`'s settings as one schema (docs/DAYLIGHT.md): the Perez sky from measured
// light for one set of inputs (models/perez_allweather.h through the `perez` model's irradiance
// parameters), or, with an EPW weather file, the annual sky matrix (daylight/sky_matrix.h).
#pragma once

#include <string>

#include "skylight/core/parameters.h"
#include "skylight/daylight/sky_matrix.h"
#include "skylight/models/perez.h"

namespace skylight::daylight {

struct DaylightRequest {
  PerezParameters sky;    // --dni .. --compat (PerezParameters::irradiance_schema()); the sun apart
  std::string epw;        // --epw FILE: the annual matrix instead of one sky
  MatrixSettings matrix;  // --patches .. --quantity (with --epw)

  // The irradiance parameters, --epw and the matrix settings.
  static const ParameterSchema<DaylightRequest>& schema();
  // The names of the parameters that only one of the two modes reads.
  static const std::vector<std::string>& one_sky_only();
  static const std::vector<std::string>& matrix_only();
};

}  // namespace skylight::daylight
