// The EXIF of a photograph's capture (JPEG, TIFF, DNG and files derived from them), read with
// libexif: when and where it was taken and its focal length, so that `skylight estimate` takes
// the sun from the SPA and the fisheye's scale from the file (docs/ESTIMATE.md, "Real photos").
#pragma once

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace skylight::io {

struct ExifInfo {
  std::string make, model;                // IFD0 Make, Model (empty when absent)
  std::optional<std::string> date_time;   // DateTimeOriginal "YYYY:MM:DD HH:MM:SS"
  std::optional<std::string> utc_offset;  // OffsetTimeOriginal "+HH:MM" (EXIF 2.31)
  std::optional<double> focal_length_mm;  // FocalLength
  // The focal length in pixels of the capture: FocalLength x FocalPlaneXResolution (per inch,
  // cm or mm by FocalPlaneResolutionUnit); absent without both.
  std::optional<double> focal_length_px;
  std::optional<int> pixel_width;  // PixelXDimension: the capture's width [px]
  std::optional<double> latitude_deg, longitude_deg, altitude_m;  // GPS IFD, signed by their refs

  // The capture time as ISO 8601 with its UTC offset, "2024-06-21T15:00:00+02:00": the offset
  // from `utc_offset_override` (e.g. a --utc-offset flag) or the file's. InvalidArgument naming
  // `name` and what is missing (no DateTimeOriginal, no offset: EXIF before 2.31 has none).
  std::string time_iso8601(const std::optional<std::string>& utc_offset_override,
                           const std::string& name) const;
};

// Reads the EXIF of a JPEG (its APP1 segment) or a TIFF / DNG (its IFDs). IoError when the file
// cannot be read; InvalidArgument naming the file when it is neither or carries no EXIF.
ExifInfo read_exif(const std::filesystem::path& path);
// The same from the file's bytes (`name` for messages).
ExifInfo parse_exif(std::span<const char> bytes, std::string_view name);

}  // namespace skylight::io
