// Float images and their files. Pixels are stored row-major, row 0 at the top, channels
// interleaved. Values are linear (radiance, luminance, ...) unless a function says otherwise.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace skylight::io {

struct ImageF {
  int width = 0;
  int height = 0;
  int channels = 3;         // 1 (luminance) or 3 (RGB / XYZ)
  std::vector<float> data;  // width * height * channels

  ImageF() = default;
  ImageF(int w, int h, int c)
      : width(w),
        height(h),
        channels(c),
        data(static_cast<size_t>(w) * static_cast<size_t>(h) * static_cast<size_t>(c), 0.0f) {}
  float* pixel(int x, int y) {
    return data.data() + (static_cast<size_t>(y) * width + x) * channels;
  }
  const float* pixel(int x, int y) const {
    return data.data() + (static_cast<size_t>(y) * width + x) * channels;
  }
};

// 8-bit sRGB-encoded RGB image (previews, false-colour maps).
struct Image8 {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> data;  // width * height * 3

  Image8() = default;
  Image8(int w, int h)
      : width(w), height(h), data(static_cast<size_t>(w) * static_cast<size_t>(h) * 3, 0) {}
  std::uint8_t* pixel(int x, int y) {
    return data.data() + (static_cast<size_t>(y) * width + x) * 3;
  }
  const std::uint8_t* pixel(int x, int y) const {
    return data.data() + (static_cast<size_t>(y) * width + x) * 3;
  }
};

// Key/value strings recorded in the file where the format allows (EXR header attributes,
// Radiance .hdr header lines, PNG tEXt chunks; PFM has no room for metadata).
using Metadata = std::vector<std::pair<std::string, std::string>>;

enum class ImageFormat { exr, hdr, pfm, png };
// Format from the file extension (.exr, .hdr, .pfm, .png; case-insensitive);
// throws skylight::InvalidArgument naming the path otherwise.
ImageFormat format_from_path(const std::filesystem::path& path);

// Writes a float image atomically (temporary file in the same directory + rename), choosing the
// format from the extension. EXR: 32-bit float channels (R,G,B or Y) with metadata as string
// attributes. HDR: RGBE (negative values clamped to 0 first: RGBE cannot store them). PFM: float
// little-endian. PNG holds 8-bit data: InvalidArgument (tone-map first, render/tonemap.h).
// Throws skylight::IoError naming the path on failure, InvalidArgument for an empty image.
void write_image(const std::filesystem::path& path, const ImageF& image, const Metadata& meta = {});
// Writes an 8-bit image as PNG, atomically.
void write_png(const std::filesystem::path& path, const Image8& image, const Metadata& meta = {});

// What read_image accepts.
struct ReadImageOptions {
  // The largest image [pixels]: a header that asks for more is refused before any pixel memory
  // is allocated. Default: the largest image `skylight render` writes (32768 x 32768).
  std::int64_t max_pixels = std::int64_t{32768} * 32768;
  // NaN and infinite pixels are refused (no output of the project holds them); true reads the
  // values as stored (bit-exact round trips of any float).
  bool allow_non_finite = false;
};

// Reads an EXR (R,G,B or Y channels, any pixel type converted to float), PFM or HDR file.
// Throws skylight::IoError naming the path on a missing or corrupt file, InvalidArgument naming
// it for an image over options.max_pixels or (unless allowed) a non-finite pixel.
ImageF read_image(const std::filesystem::path& path, const ReadImageOptions& options = {});
// Reads an 8-bit PNG (grey, grey + alpha, RGB or RGBA; alpha dropped, grey copied to R, G, B) as
// stored, without any conversion (e.g. masks). Throws skylight::IoError naming the path on a
// missing or corrupt file, InvalidArgument for an image over options.max_pixels (checked from the
// header before any pixel memory is allocated; allow_non_finite does not apply to 8-bit data).
Image8 read_png(const std::filesystem::path& path, const ReadImageOptions& options = {});
// Reads a one-channel image (depth maps, masks): EXR channel Z, else Y, else R (any pixel type as
// float); PFM `Pf`, or the first channel of `PF`; a 16-bit PNG (grey, or its first channel) as
// v / 65535 in [0, 1]. Errors as read_image; an 8-bit PNG or .hdr is InvalidArgument naming it.
ImageF read_scalar_image(const std::filesystem::path& path, const ReadImageOptions& options = {});

// Reads the string attributes of an EXR header.
Metadata read_exr_metadata(const std::filesystem::path& path);

}  // namespace skylight::io
