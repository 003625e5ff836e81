// The haze operations as a user asks for them (`skylight haze ...`, the Python package; Morales,
// Oishi & Ikeuchi 2017, docs/HAZE.md): every option declared once here with its schema, and what
// turns them into the library's settings: the atmosphere, the camera's sensitivities, where the
// airlight I^inf comes from (a constant, a spectral sky model through the camera, eq. 7, or a sky
// photo's horizon, eqs. 12-13), the image's own camera (eqs. 20-23) and the operation's settings.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "skylight/core/camera.h"
#include "skylight/core/parameters.h"
#include "skylight/estimate/photo.h"
#include "skylight/haze/airlight_field.h"
#include "skylight/haze/coefficients.h"
#include "skylight/haze/image_haze.h"
#include "skylight/haze/positioning.h"
#include "skylight/haze/sensitivity.h"
#include "skylight/haze/sky_segmentation.h"

namespace skylight::haze {

// --turbidity (required), --altitude, --variant.
const ParameterSchema<Atmosphere>& atmosphere_schema();

// --camera NAME (the embedded PhysLight cameras) or --camera-csv FILE.
struct SensitivityOptions {
  std::string camera, camera_csv;
  static const ParameterSchema<SensitivityOptions>& schema();
  // The sensitivities (InvalidArgument when neither is given).
  CameraSensitivity sensitivity() const;
};

// The image's own camera (Morales 2017 eqs. 20-23; positioning.h): a pinhole from --vfov or
// --hfov and --heading, --pitch, --roll, or the OpenGL matrices --view-matrix and
// --projection-matrix. Without one every pixel gets one airlight.
struct ImageCameraOptions {
  std::optional<double> vfov_deg, hfov_deg;
  std::optional<double> heading_deg, pitch_deg, roll_deg;
  std::vector<double> view_matrix, projection_matrix;  // 16 values row-major, or empty
  static const ParameterSchema<ImageCameraOptions>& schema();
  // Whether the image has a camera (any of its options given).
  bool given() const;
  // The positioning of a width x height image; near and far are the pinhole's clip planes (the
  // depth map's when normalised; directions do not depend on them). nullopt without a camera;
  // InvalidArgument for angles without a field of view.
  std::optional<ImagePositioning> positioning(int width, int height, double near_m,
                                              double far_m) const;
};

// Where the airlight I^inf comes from: --airlight R,G,B; --sky-model NAME (a spectral model at the
// turbidity, its sun --sun-zenith/--sun-azimuth, seen towards --view-elevation/--view-azimuth);
// --sky PHOTO (its horizon region: --horizon-region watershed|band, --sky-mask, the photo's
// --sky-projection and fisheye options).
struct AirlightOptions {
  std::vector<double> airlight;
  std::string sky_model, sky_photo, sky_mask;
  // The sky photo's projection (--sky-projection, fisheye by default) and lens.
  ImageOptions sky_image = estimate::photo_image_options(Projection::fisheye, "sky-projection",
                                                         "--sky: the sky photo's layout")
                               .defaults();
  HorizonRegion horizon_region = HorizonRegion::watershed;
  double sun_zenith_deg = 45.0, sun_azimuth_deg = 180.0;
  std::optional<double> view_elevation_deg, view_azimuth_deg;
  static const ParameterSchema<AirlightOptions>& schema();
};

// The models --sky-model takes: the registry's spectral models with a turbidity (preetham, hosek).
std::vector<std::string> airlight_models();

// The airlight of AirlightOptions at any turbidity. The sky photo's horizon region (the watershed
// or the band, sky_segmentation.h) is found once; only zeta (eq. 13) depends on T and theta.
class AirlightSource {
 public:
  explicit AirlightSource(AirlightOptions options);
  // One airlight for the image at turbidity t (Morales 2017 eq. 10).
  Rgb3 at(double t, const CameraSensitivity& camera) const;
  // Per pixel through the image's camera at turbidity t (§6.2 step 3); null for a constant
  // --airlight. InvalidArgument with --view-elevation/--view-azimuth (each pixel sees its own).
  std::shared_ptr<const AirlightMap> per_pixel(double t, const CameraSensitivity& camera,
                                               const ImagePositioning& image) const;
  // Whether the airlight comes from a sky photo (its files are then inputs too).
  const AirlightOptions& options() const { return options_; }

 private:
  PhotoAirlight photo_horizon(double t, double theta) const;
  std::unique_ptr<SkyModel> model_at(double t) const;

  AirlightOptions options_;
  mutable std::optional<PhotoAirlight> photo_;
};

// The options of add, retarget and remove (and composite's depth): --target-turbidity (retarget
// only), the depth map's --near/--far, --min-transmission.
struct HazeOptions {
  std::optional<double> target_turbidity;
  std::optional<double> near_m, far_m;
  double min_transmission = kDefaultMinTransmission;
  static const ParameterSchema<HazeOptions>& schema();
};

// The settings of an operation: the atmosphere, the airlights at T_s (and T_t), per pixel through
// the image's camera when it has one (width x height). InvalidArgument for --target-turbidity
// without retarget or retarget without it.
HazeSettings haze_settings(HazeOperation operation, const Atmosphere& air,
                           const HazeOptions& options, const CameraSensitivity& camera,
                           const AirlightSource& airlight, const ImageCameraOptions& image_camera,
                           int width, int height);

// An image operation (add, retarget, remove; composite as add) from its schema's values (the
// operation's parameters in `operations`, parsed): the atmosphere (validated), the camera's
// sensitivity, the depth options and the settings for an image of width x height. The CLI and the
// Python package build their operations from this.
struct ImageHazeRequest {
  Atmosphere air;
  CameraSensitivity camera;
  HazeOptions options;
  HazeSettings settings;
};
ImageHazeRequest image_haze_request(HazeOperation operation, const ParameterValues& given,
                                    int width, int height);

// The coverage of a composited object without an alpha map: 1 where its depth is > 0.
io::ImageF coverage_from_depth(const io::ImageF& depth);

// What a haze output records: the operation, camera, variant, turbidity, altitude, the airlight
// (constant R,G,B or "per pixel") and the target turbidity.
std::vector<std::pair<std::string, std::string>> haze_metadata(std::string_view operation,
                                                               const Atmosphere& air,
                                                               const CameraSensitivity& camera,
                                                               const HazeSettings& settings);

// `haze coefficients`: the wavelength (--wavelength); `haze attenuation`: the path (--distance).
struct CoefficientsOptions {
  double wavelength_nm = 550.0;
  static const ParameterSchema<CoefficientsOptions>& schema();
};
struct AttenuationOptions {
  double distance_m = 1000.0;
  static const ParameterSchema<AttenuationOptions>& schema();
};

// The choices of --variant and --horizon-region as text.
std::string_view to_string(HorizonRegion region);

}  // namespace skylight::haze
