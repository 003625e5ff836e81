// Measured skies placed in the sky: the sun of a Kider capture (io/kider.h) from its local time and
// site by the NREL SPA, and the sun's azimuth estimated from the measured sky's axis of symmetry
// (the drift fix of Bruneton 2017's harness; docs/MEASURED.md, "The sun of a capture").
#pragma once

#include <optional>
#include <string>

#include "skylight/core/frame.h"
#include "skylight/io/kider.h"

namespace skylight::analysis {

// Where and when the captures were taken. The defaults are Kider et al. 2014's site (the roof of
// Rhodes Hall, Cornell University) and its clocks (EDT).
struct KiderSite {
  double latitude_deg = 42.443449;
  double longitude_deg = -76.481962;
  double elevation_m = 0.0;  // not published; the SPA's parallax and refraction barely move
  std::string utc_offset = "-04:00";  // the captures' local time (EDT)
};

struct CaptureSun {
  SunPosition sun;                         // what the comparison uses
  double spa_zenith = 0.0;                 // [rad] by the SPA at the capture's time
  double spa_azimuth = 0.0;                // [rad] by the SPA, from north towards east
  std::optional<double> symmetry_azimuth;  // [rad] the sky's axis of symmetry, when asked for
};

// The axis of symmetry of the capture's luminance, searched within +-kSymmetrySearchDeg of
// `initial_azimuth` [rad] in steps of kSymmetryStepDeg: the azimuth a that minimises the sum over
// the rings of 8 samples or more of |log L(phi) - log L(2 a - phi)|, L interpolated linearly and
// periodically in azimuth along each ring (Bruneton's harness searches +-20 deg in 0.2 deg steps
// over his interpolated hemisphere). Returns [rad] in [0, 2 pi).
inline constexpr double kSymmetrySearchDeg = 30.0;
inline constexpr double kSymmetryStepDeg = 0.05;
double symmetry_axis_azimuth(const io::KiderCapture& capture, double initial_azimuth);

// The capture's sun: the SPA's zenith, and its azimuth or (with `azimuth_from_symmetry`) the
// axis of symmetry searched around it. Throws InvalidArgument for a bad site or offset.
CaptureSun capture_sun(const io::KiderCapture& capture, const KiderSite& site,
                       bool azimuth_from_symmetry);

}  // namespace skylight::analysis
