// Measured clear skies in the layout of Kider et al. 2014 ("A Framework for the Experimental
// Comparison of Solar and Skydome Illumination", ACM TOG 33(6)), as republished under Apache-2.0
// (docs/MEASURED.md): a strict reader of the captures' spectral radiance and pyranometer files,
// and of the compact subset the project ships (data/measured/kider2014/).
//
// Layout of the original data (the reader finds the capture folders anywhere under the path it is
// given, up to 4 levels deep: the data set's root, a date folder, its RADIANCE folder or one
// capture folder):
//   <date>/RADIANCE/<date>___HH.MM.SS/<date>___HH.MM.SS_-_<i>____<azimuth>___<elevation>.asd.rad.txt
//   <date>/IRRADIANCE/YYYY.MM.DD.HH.MM.SS.txt
// A capture folder holds the 81 samples i = 0..80 of one scan; files ending in `.asd.txt` (the
// instrument's raw files) and anything else are ignored. A radiance file is one header line, then
// `nm<TAB>value` lines: spectral radiance [W m^-2 sr^-1 nm^-1] on a wavelength grid shared by all
// the capture's files (350-2500 nm, 1 nm, in the original). <azimuth> is in degrees
// counter-clockwise from north (north -> west: checked on the data, the brightest sky and the axis
// of symmetry lie at 360 - <azimuth> from north towards east near the sun's azimuth;
// docs/MEASURED.md), <elevation> in degrees above the horizon.
// An irradiance file: one `W/m^2<SPACE>YYYY.MM.DD.HH.MM.SS` line per reading of the pyranometer
// (global horizontal irradiance). A capture's pyranometer file is the one whose name carries the
// capture folder's date and time; none is an absent measurement, not an error.
//
// Sample 0 (north, lowest ring) is systematically wrong in the data (Bruneton 2017's harness,
// ebruneton/clear-sky-models, measured_atmosphere.cc): the reader replaces it by the mean of its
// two neighbours on the same ring, samples 1 and 31, as that harness does, and marks it.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace skylight::io {

inline constexpr int kKiderSampleCount = 81;
// The samples whose mean replaces sample 0 (its neighbours on the lowest ring, 11.25 deg to either
// side).
inline constexpr int kKiderSampleZeroNeighbours[2] = {1, 31};

// Luminance of a spectral radiance [W m^-2 sr^-1 nm^-1] on ascending wavelengths [nm]:
// 683 * integral over 380-780 nm of L(lambda) y-bar(lambda), the trapezoidal rule on the given
// wavelengths inside that interval (the CIE 1931 2-degree y-bar, core/colorimetry.h) [cd/m^2].
double luminance_380_780(const std::vector<double>& wavelengths_nm,
                         const std::vector<double>& radiance);

// A radiance file's name, parsed: `..._-_<i>____<azimuth>___<elevation>.asd.rad.txt`.
struct KiderFileName {
  int index = 0;                  // 0..80
  double file_azimuth_deg = 0.0;  // as written: counter-clockwise from north, [0, 360)
  double elevation_deg = 0.0;     // as written: above the horizon, [0, 90]
};
// nullopt for a name that is not a radiance file (raw `.asd.txt` files and others); a radiance
// file's name with a bad index, azimuth or elevation is an InvalidArgument naming it.
std::optional<KiderFileName> parse_kider_file_name(std::string_view file_name);

// One radiance file: the wavelengths [nm] (ascending) and the values. Throws InvalidArgument
// "<source> line L: ..." for a missing header, a line that is not two numbers, wavelengths that do
// not ascend, or no data.
struct KiderSpectrum {
  std::vector<double> wavelengths_nm, radiance;
};
KiderSpectrum parse_kider_radiance(std::string_view text, std::string_view source);

// One pyranometer reading.
struct PyranometerReading {
  double global_horizontal_w_m2 = 0.0;  // [W/m^2], >= 0
  std::string time;                     // as written, YYYY.MM.DD.HH.MM.SS (local time)
};
// An irradiance file. Throws InvalidArgument "<source> line L: ..." for a bad line, a negative or
// non-finite irradiance, or no readings.
std::vector<PyranometerReading> parse_pyranometer(std::string_view text, std::string_view source);

struct KiderSample {
  int index = 0;                  // the scan's sample index, 0..80
  double file_azimuth_deg = 0.0;  // as in the file name (counter-clockwise from north)
  double elevation_deg = 0.0;     // as in the file name
  double zenith = 0.0;            // [rad] view zenith angle, pi/2 - elevation
  double azimuth = 0.0;           // [rad] skylight's convention: from north towards east, [0, 2 pi)
  std::vector<double> radiance;   // [W m^-2 sr^-1 nm^-1] on the capture's wavelengths
  double luminance = 0.0;         // [cd/m^2] luminance_380_780 of the file's own spectrum
  bool replaced = false;          // sample 0: the mean of kKiderSampleZeroNeighbours
  std::string source;             // the file (or subset row) it was read from
};

struct KiderCapture {
  std::string name;                    // the capture folder's name, e.g. 2013-05-27___09.30.00
  std::string local_time;              // ISO 8601 without offset, e.g. 2013-05-27T09:30:00
  std::vector<double> wavelengths_nm;  // shared by every sample
  std::vector<KiderSample> samples;    // all 81, by index
  std::vector<PyranometerReading> pyranometer;  // empty: no pyranometer file for this capture
  std::string pyranometer_source;
  // The mean of the pyranometer's readings [W/m^2], nullopt without them.
  std::optional<double> global_horizontal_w_m2() const;
};

// Every capture under `path` (a folder of the original layout or of the shipped subset), sorted by
// name. Throws IoError for a path that cannot be read and InvalidArgument (naming the file, and
// the line where there is one) for a bad file, a capture that lacks a sample or holds one twice,
// files of one capture on different wavelengths, or a folder with no capture in it.
std::vector<KiderCapture> read_kider(const std::filesystem::path& path);

// ---- The shipped subset (data/measured/kider2014/, docs/MEASURED.md) ---------------------------
// Two CSV files, comment lines starting with '#' first:
//   radiance.csv:    capture,index,file_azimuth_deg,elevation_deg,luminance_cd_m2,<nm>,<nm>,...
//                    one row per sample, the spectrum on the header's wavelengths and the luminance
//                    of the original 1 nm spectrum (sample 0 as measured: the reader replaces it);
//   pyranometer.csv: capture,global_horizontal_w_m2,time
inline constexpr std::string_view kKiderSubsetRadianceFile = "radiance.csv";
inline constexpr std::string_view kKiderSubsetPyranometerFile = "pyranometer.csv";
// The embedded copy's paths inside data/.
inline constexpr std::string_view kKiderSubsetDataDir = "measured/kider2014";
std::vector<KiderCapture> parse_kider_subset(std::string_view radiance_csv,
                                             std::string_view pyranometer_csv,
                                             std::string_view source);
// The shipped subset, from the library's embedded copy.
std::vector<KiderCapture> shipped_kider_subset();

}  // namespace skylight::io
