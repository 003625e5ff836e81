// Camera spectral sensitivities q_c(lambda), c in {r, g, b} (Morales 2017 eq. 7): the embedded
// PhysLight measurements (data/camera_sensitivity/PROVENANCE.md) by name, or a user CSV.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/core/spectrum.h"

namespace skylight::haze {

// The visible range of eqs. 7 and 11 [nm].
inline constexpr double kVisibleFirstNm = 380.0;
inline constexpr double kVisibleLastNm = 780.0;

struct CameraSensitivity {
  std::string name;                 // e.g. "canon-eos-5d", or the CSV's path
  std::string description;          // "Canon EOS 5D"
  std::array<Spectrum, 3> channel;  // q_r, q_g, q_b [relative], defined over 380 .. 780 nm
};

// Names of the embedded cameras: manufacturer and model lower-cased, spaces as hyphens
// ("canon-eos-5d", "sony-ilce-7m3"), sorted.
std::vector<std::string> camera_names();

// The embedded camera `name`; InvalidArgument listing the known names otherwise.
const CameraSensitivity& find_camera(std::string_view name);

// A user CSV: a header line `nm,r,g,b`, then one row per wavelength [nm] (strictly ascending,
// covering 380 .. 780 nm), sensitivities finite and >= 0, each channel's sum > 0. InvalidArgument
// naming the file, line and field for bad content; IoError when the file cannot be read.
CameraSensitivity load_camera_csv(const std::filesystem::path& path);
// The same from text; `source` names it in messages.
CameraSensitivity parse_camera_csv(std::string_view text, const std::string& source);

}  // namespace skylight::haze
