// Sky-luminance scans (measured or synthetic) for the validation report: the CSV format, the
// 145 Tregenza patches, a reproducible synthetic scan and the error statistics of a model against a
// scan.
//
// CSV format (docs/REPORT.md): an optional block of comment lines starting with '#', which may set
// the sun position as `# sun_azimuth_deg = A` (from north towards east, -360-360) and
// `# sun_elevation_deg = E` (0-90); then the header `azimuth_deg,elevation_deg,luminance_cd_m2`
// (columns in any order, further columns ignored) and one row per sample: azimuth [deg] from north
// towards east (-360-360), elevation [deg] (0-90), luminance [cd/m^2] (> 0). Blank lines and
// further comment lines are skipped; CRLF is accepted.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/core/frame.h"
#include "skylight/models/sky_model.h"

namespace skylight::analysis {

struct LuminanceSample {
  double azimuth = 0.0;    // [rad], from north towards east, [0, 2 pi)
  double elevation = 0.0;  // [rad], [0, pi/2]
  double luminance = 0.0;  // [cd/m^2], > 0
  std::size_t line = 0;    // source line (1-based)
};

struct SkyScan {
  std::string source;                   // file name (or label) used in messages
  std::optional<double> sun_azimuth;    // [rad] from the comment lines, if given
  std::optional<double> sun_elevation;  // [rad] from the comment lines, if given
  std::vector<LuminanceSample> samples;
};

// Parses the CSV text. Throws InvalidArgument "<source> line L column C: ..." for a field that is
// not a number (NaN and infinities included; one that overflows or underflows to 0 is said so:
// number_problem) or out of range, "<source> line L: expected N
// fields, found M" for a missing column, and names a missing header column or a bad sun comment.
SkyScan parse_sky_scan(std::string_view text, std::string source);
// Reads and parses a file (IoError naming the path if it cannot be read).
SkyScan read_sky_scan(const std::filesystem::path& path);
// The CSV text of a scan (comment lines first, then the header and one row per sample, 6
// significant digits for the luminance).
std::string format_sky_scan(const SkyScan& scan, const std::vector<std::string>& comments);

// Tregenza (1987) sky subdivision: 145 patch centres in 8 bands at elevations 6, 18, ..., 78 deg
// (12 deg apart) with 30, 30, 24, 24, 18, 12, 6 patches and one zenith patch at 90 deg. In each
// band the first patch is at azimuth 0 (north) and the others follow every 360/n deg towards
// east. Returned as (azimuth, elevation) [rad].
struct PatchCentre {
  double azimuth = 0.0, elevation = 0.0;
};
std::vector<PatchCentre> tregenza_patch_centres();
inline constexpr int kTregenzaPatchCount = 145;

// The shipped synthetic example (data/measurements/): the CIE type-7 sky with the Kittler-Darula
// typical zenith luminance at the 145 Tregenza patch centres, each multiplied by (1 + noise u),
// u uniform in [-1, 1) from SplitMix64 seeded with `seed` (deterministic on every platform).
struct SyntheticScanSettings {
  int cie_type = 7;
  double sun_azimuth = deg_to_rad(165.0);   // [rad]
  double sun_elevation = deg_to_rad(35.0);  // [rad]
  double noise = 0.05;                      // relative amplitude, [0, 1)
  std::uint64_t seed = 20070101;
};
SkyScan synthetic_tregenza_scan(const SyntheticScanSettings& settings = {});
// The comment lines written at the top of the shipped example file.
std::vector<std::string> synthetic_scan_comments(const SyntheticScanSettings& settings = {});
// Path of the shipped example inside data/ (embedded in the library).
inline constexpr std::string_view kSyntheticScanDataPath =
    "measurements/synthetic_tregenza_cie7.csv";

// Error statistics of a model against a scan, over the samples further than `sun_exclusion` from
// the sun (the model's sky only, no solar disc), with d = log10(L_model / L_measured):
//  * absolute: the model's own absolute luminance;
//  * relative: both normalised to the zenith, i.e. the model scaled by L_measured / L_model at the
//    sample with the highest elevation (the zenith patch of a Tregenza scan).
// rms = sqrt(mean d^2), bias = mean d (log10 units; 10^bias - 1 is the mean relative bias).
struct ScanErrors {
  double rms_log10_absolute = 0.0, bias_log10_absolute = 0.0;
  double rms_log10_relative = 0.0, bias_log10_relative = 0.0;
  std::size_t samples_used = 0;  // samples outside the exclusion with a positive model value
};
// The model must have been built for the scan's sun position. Throws InvalidArgument if no sample
// is usable.
ScanErrors compare_to_scan(const SkyModel& model, const SkyScan& scan, double sun_exclusion);

}  // namespace skylight::analysis
