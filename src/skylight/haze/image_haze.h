// Aerial perspective on images with a depth map (Morales et al. 2017 §4, §6, §7.2.3; docs/HAZE.md):
// add haze (eq. 10), re-target from turbidity T_s to T_t (eq. 26), remove haze (eq. 10 inverted),
// and composite a virtual object into a hazy photo. Every output pixel is a function of the
// input pixel, its depth and a few uniforms (the airlights and two Gamma tables in distance), so
// the CPU kernel and a fragment shader compute the same thing.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "skylight/core/camera.h"
#include "skylight/core/math.h"
#include "skylight/haze/attenuation.h"
#include "skylight/io/image.h"
#include "skylight/models/sky_model.h"

namespace skylight::haze {

// A depth map as stored: metres, or (with near and far) the normalised depth s_bar in [0, 1] of
// eq. 19.
struct DepthEncoding {
  std::optional<double> near_m, far_m;  // both or neither; 0 < near < far
};
// Throws InvalidArgument unless near and far are both absent or 0 < near < far.
void validate(const DepthEncoding& encoding);

// Eq. 19: s = s_near / (1 - s_bar (1 - s_near / s_far)) [m].
double depth_from_normalised(double s_bar, double near_m, double far_m);

// The depth map in metres (one channel), checked: the size of `image_width` x `image_height`
// (InvalidArgument naming both sizes otherwise), every value finite and >= 0 (in [0, 1] when
// normalised). `what` names the map in messages.
io::ImageF depth_in_metres(const io::ImageF& depth, const DepthEncoding& encoding, int image_width,
                           int image_height, std::string_view what);

enum class HazeOperation { add, remove, retarget };

// Where Gamma is tiny, removing haze amplifies noise without bound (I_0 = (I - A (1 - Gamma)) /
// Gamma). Remove and re-target towards clearer air use max(Gamma_s, this) instead of Gamma_s,
// so that no pixel's own light is amplified more than 1 / this; outputs are clamped at 0.
inline constexpr double kDefaultMinTransmission = 0.05;

// The largest interpolation error the Gamma tables may add [1] (far below 8-bit quantisation).
inline constexpr double kDefaultTableError = 1e-5;

// A per-pixel airlight I^inf(T, phi, theta) (Morales 2017 §6.2 step 3; haze/airlight_field.h
// builds them): an RGB image of the operation's image size, every value finite and > 0.
class AirlightMap {
 public:
  // InvalidArgument unless `rgb` has 3 channels and every value is finite and > 0.
  explicit AirlightMap(io::ImageF rgb);
  const io::ImageF& rgb() const { return rgb_; }

 private:
  io::ImageF rgb_;
};

struct HazeSettings {
  HazeOperation operation = HazeOperation::add;
  Atmosphere source;  // add: the haze added; remove, retarget: the photo's (T_s)
  std::optional<double> target_turbidity;  // retarget: T_t (required)
  Rgb3 airlight_source{1.0, 1.0, 1.0};     // I^inf at T_s (add, remove) [image units], > 0
  Rgb3 airlight_target{1.0, 1.0, 1.0};     // I^inf at T_t (retarget)
  // Per pixel instead (both for retarget, the source alone otherwise; of the image's size): they
  // replace the constant airlights above.
  std::shared_ptr<const AirlightMap> airlight_source_map, airlight_target_map;
  double min_transmission = kDefaultMinTransmission;  // (0, 1]
  double table_error = kDefaultTableError;
};

// What apply_haze did (for the CLI's report and the docs).
struct HazeReport {
  double table_error_bound = 0.0;  // the Gamma tables' interpolation bound
  std::size_t table_entries = 0;
  std::size_t clamped_transmission_pixels = 0;  // pixels where Gamma_s < min_transmission
};

// What every pixel of an operation reads besides its own value and depth: the Gamma_s and
// Gamma_t tables on one grid (eq. 11, AttenuationTable) and the uniforms of eq. 26. The CPU kernel
// (apply_haze_in_place) and the fragment shader (gpu/haze.h) evaluate the same thing from it:
//   pos = s / step, i = min(floor(pos), entries - 2), f = pos - i,
//   Gamma = G[i] + f (G[i + 1] - G[i]) per table, r = Gamma_t / max(Gamma_s, min_transmission),
//   I_out = max(0, I scale r + airlight_target (1 - r)),
// with, when airlight_target_map is set, airlight_target the pixel's value in it and scale its
// ratio to the pixel's value in airlight_source_map (1 when that is null: add and remove).
struct HazeKernel {
  AttenuationTable source, target;  // empty gamma: identically 1 (source: add, target: remove)
  double step_m = 1.0;              // the common table step [m]
  std::size_t entries = 0;          // entries of each non-empty table
  double min_transmission = kDefaultMinTransmission;
  Rgb3 airlight_target{};  // I^inf_t [image units]
  Rgb3 scale{};            // I^inf_t / I^inf_s [1]
  std::shared_ptr<const AirlightMap> airlight_target_map, airlight_source_map;  // per pixel
  double error_bound() const { return std::max(source.error_bound, target.error_bound); }
};

// The kernel of `settings` for depths in [0, max_depth_m] (checked: InvalidArgument for bad
// settings, as apply_haze).
HazeKernel haze_kernel(double max_depth_m, const CameraSensitivity& camera,
                       const HazeSettings& settings);

// The operation on a 3-channel image with a depth map in metres (same size, one channel): fast
// path (Gamma tables + threads). Gamma_s = 1 for add (eq. 10 with Gamma_t = Gamma), Gamma_t = 1
// for remove; every operation is then eq. 26:
//   I_out = I (A_t Gamma_t) / (A_s g_s) + A_t (1 - Gamma_t / g_s),  g_s = max(Gamma_s, min),
// clamped at 0.
io::ImageF apply_haze(const io::ImageF& image, const io::ImageF& depth_m,
                      const CameraSensitivity& camera, const HazeSettings& settings,
                      HazeReport* report = nullptr);

// The same in place (no output buffer: per-frame use).
void apply_haze_in_place(io::ImageF& image, const io::ImageF& depth_m,
                         const CameraSensitivity& camera, const HazeSettings& settings,
                         HazeReport* report = nullptr);

// The same with Gamma integrated exactly (eq. 11, 81 wavelengths) at every pixel, one thread: the
// slow reference of the tests and the benchmark.
io::ImageF apply_haze_exact(const io::ImageF& image, const io::ImageF& depth_m,
                            const CameraSensitivity& camera, const HazeSettings& settings);

// A virtual object (RGB, coverage alpha in [0, 1], depth in metres) given haze at T (eq. 10 with
// `settings` as for add) and laid over the background photo (which already shows that haze):
// out = alpha I_VO,hazed + (1 - alpha) I_BG (Morales §6.2 step 3).
io::ImageF composite(const io::ImageF& background, const io::ImageF& object,
                     const io::ImageF& alpha, const io::ImageF& object_depth_m,
                     const CameraSensitivity& camera, const HazeSettings& settings);

// The checks of composite (RGB background and object of one size, a one-channel alpha of that
// size with every value in [0, 1]): InvalidArgument naming what differs. The GL composite
// (gpu/haze.h) checks the same.
void check_composite_inputs(const io::ImageF& background, const io::ImageF& object,
                            const io::ImageF& alpha);

// The airlight I^inf_c of a sky model in direction `view`: its spectral radiance seen through the
// camera (eq. 7, trapezoid on the 5 nm grid) [W m^-2 sr^-1 x relative sensitivity].
// InvalidArgument when the model has no spectral output in 380 .. 780 nm.
Rgb3 sky_model_airlight(const SkyModel& model, Vec3 view, const CameraSensitivity& camera);

// Eq. 13: zeta(T, theta, theta') = the Preetham-based ratio of the sky intensity at zenith angle
// theta to that at theta' [1]; cos theta clamped at 0.01 (the Perez gradation's clamp,
// docs/CONVENTIONS.md) so that the horizon is finite. Eq. 12: I^inf(T, theta) = I^inf(theta') zeta.
double zeta(double turbidity, double theta, double theta_prime);

// The airlight from a sky photo's horizon region (eqs. 12-13).
// Eq. 12 takes I^inf(theta') "with the same azimuth phi" as the view: the horizon region is
// also split into kHorizonSectors sectors of azimuth, each with its own brightest pixels.
inline constexpr int kHorizonSectors = 36;

struct HorizonSector {
  double azimuth = 0.0;      // the sector's centre [rad], north 0, east pi/2
  Rgb3 horizon{};            // I^inf(theta') of the sector's brightest 1 % (at least one pixel)
  double theta_prime = 0.0;  // their mean zenith angle [rad]
  std::size_t pixels = 0;
};

struct PhotoAirlight {
  Rgb3 airlight{};           // I^inf(T, theta) [photo units], from the whole region
  Rgb3 horizon{};            // I^inf(theta'): the mean of the brightest horizon pixels
  double theta_prime = 0.0;  // their mean zenith angle [rad]
  std::size_t pixels = 0;    // how many were averaged
  // The same per sector of azimuth, ascending, the sectors the region reaches only (the
  // per-pixel airlight interpolates between them in azimuth, haze/airlight_field.h).
  std::vector<HorizonSector> sectors;
};

// Default height of the horizon region above the horizon [rad].
inline constexpr double kHorizonBand = 10.0 * kDegree;

// Eq. 12: among the photo's pixels that see the sky between the horizon and `band` above it, the
// brightest 1 % (at least one) by luminance (Rec. 709) are averaged to I^inf(theta') at their mean
// zenith angle theta'; then I^inf(T, theta) = I^inf(theta') zeta(T, theta, theta') (eq. 13) for
// the zenith angle `theta` [rad] seen behind the scene (pi/2: the horizon). InvalidArgument when
// no pixel lies in the band or the photo is not RGB.
PhotoAirlight photo_airlight(const io::ImageF& sky, const Camera& camera, double turbidity,
                             double theta, double band = kHorizonBand);

// Eq. 12 on a given horizon region (`region`: one byte per pixel, nonzero = in the region; its
// pixels below the horizon or outside the image circle are ignored): the brightest 1 % as above.
// photo_airlight's band and the watershed region of haze/sky_segmentation.h both end here.
PhotoAirlight region_airlight(const io::ImageF& sky, const Camera& camera,
                              const std::vector<std::uint8_t>& region, double turbidity,
                              double theta);

}  // namespace skylight::haze
