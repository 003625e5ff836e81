// Light on a plane from any sky (`skylight irradiance`, docs/IRRADIANCE.md): the plane's settings
// as one schema, and the light of one sky on one plane in three channels, each by part (direct,
// sky diffuse, ground diffuse; the sky's circumsolar, horizon-band and remaining parts):
//  * irradiance [W/m^2]: broadband, where the sky's level is measured (MeasuredLight: the Perez
//    sky of --dni/--dhi); the other models give luminance and spectra, not broadband irradiance;
//  * illuminance [lx]: every model (the direct part where the model has a sun or measured light);
//  * melanopic equivalent daylight illuminance [lx] (CIE S 026): the spectral models.
// Three methods: `sky` (the model's own luminance integrated over the plane's view,
// daylight/plane_sky.h), `perez1990` and `isotropic` (daylight/transposition.h).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "skylight/core/parameters.h"
#include "skylight/daylight/plane_sky.h"
#include "skylight/daylight/sky_matrix.h"
#include "skylight/daylight/transposition.h"
#include "skylight/io/horizon.h"
#include "skylight/models/sky_model.h"

namespace skylight::daylight {

enum class Transposition { sky, perez1990, isotropic };

struct PlaneSettings {
  double tilt_deg = 0.0;               // --tilt, [0, 180]
  double surface_azimuth_deg = 180.0;  // --surface-azimuth, [0, 360], from north towards east
  std::optional<double> albedo;        // --albedo, [0, 1]
  std::string horizon;                 // --horizon FILE (io/horizon.h); empty: flat
  Transposition transposition = Transposition::sky;  // --transposition

  static const ParameterSchema<PlaneSettings>& schema();
  Plane plane() const;
};

// One plane, ready for many skies: its weights on the sky grids (the `sky` method; the horizon's
// views) and the horizon. The horizon is referenced (it must outlive the context).
struct PlaneContext {
  Plane plane{};
  Transposition method = Transposition::sky;
  const io::HorizonProfile* horizon = nullptr;
  PlaneWeights weights, spectral_weights;
  HorizonViews views;
};
PlaneContext plane_context(const Plane& plane, Transposition method,
                           const io::HorizonProfile& horizon);
// The coarser grid of the melanopic channel (spectra cost a model evaluation per wavelength):
// 2 + 22 rings x 72 sectors.
const SkyGrid& spectral_sky_grid();

// The light of one sky on the plane.
struct PlaneChannels {
  std::optional<PlaneLight> irradiance, illuminance;
  std::optional<double> melanopic_edi_lx;  // on the plane, all parts
  std::optional<Perez1990> perez;          // perez1990: the hour's state
  double angle_of_incidence = 0.0;         // of the sun [rad]
  bool sun_open = false;                   // the sun is up and above the skyline
  double sky_normalisation = 1.0;          // sky with measured light: grid / model level
  std::vector<std::string> notes;          // why a channel or a part is absent
};
// `albedo`: the ground's reflectance. Throws InvalidArgument for perez1990 on a sky without
// measured light (its F1, F2 need the direct and diffuse irradiance).
PlaneChannels plane_light(const SkyModel& model, const PlaneContext& plane, double albedo);

// The parts of plane_light that the annual series shares (daylight/plane_series.h):
//  * the `sky` method for a sky of measured light: L, the sky's relative luminance at the cells of
//    the context's grid, scaled so that its horizontal integral is the measured diffuse light
//    (illuminance and irradiance alike); the direct light from the measured direct normal light;
//  * the transpositions (perez1990, isotropic) of measured light.
PlaneChannels measured_sky_light(const std::vector<float>& L, const MeasuredLight& light,
                                 const SunPosition& sun, const PlaneContext& plane, double albedo);
PlaneChannels transposed_measured_light(const MeasuredLight& light, const SunPosition& sun,
                                        const PlaneContext& plane, double albedo);

}  // namespace skylight::daylight
