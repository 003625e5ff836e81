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

namespace skylight::render {

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
// little-endian. PNG: a tone-mapped 8-bit preview (tonemap_preview with default exposure).
// Throws skylight::IoError naming the path on failure, InvalidArgument for an empty image.
void write_image(const std::filesystem::path& path, const ImageF& image, const Metadata& meta = {});
// Writes an 8-bit image as PNG, atomically.
void write_png(const std::filesystem::path& path, const Image8& image, const Metadata& meta = {});
// Writes bytes (e.g. HTML, SVG, JSON text) to a file atomically, like the image writers.
void write_text_file(const std::filesystem::path& path, std::string_view content);

// Reads an EXR (R,G,B or Y channels, any pixel type converted to float), PFM or HDR file.
// Throws skylight::IoError naming the path on a missing or corrupt file.
ImageF read_image(const std::filesystem::path& path);
// Reads the string attributes of an EXR header.
Metadata read_exr_metadata(const std::filesystem::path& path);

// Linear -> 8-bit preview: scales so that the given percentile of luminance maps to `white`
// (auto exposure), applies the Reinhard operator L/(1+L) per channel ratio and the sRGB OETF.
struct ToneMapOptions {
  double percentile = 0.99;  // luminance percentile that sets the exposure, (0, 1]
  double exposure = 1.0;     // extra linear factor after auto exposure
};
Image8 tonemap_preview(const ImageF& image, const ToneMapOptions& options = {});

// Log-luminance false-colour map with a legend bar (style of Zotti et al. 2007, Figs. 4-7: each
// decade of magnitude gets its own hue, brightness ramps within the decade). `luminance` is a
// one-channel image; pixels with a zero, negative or non-finite value (log undefined), or flagged
// in `mask` (same size, non-zero = outside the image), are drawn dark grey (40, 40, 40). Decades
// from 10^log10_min to 10^log10_max.
struct FalseColourOptions {
  double log10_min = 0.0;
  double log10_max = 6.0;
  std::string unit = "cd/m2";  // printed on the legend
  bool legend = true;
};
Image8 false_colour(const ImageF& luminance, const FalseColourOptions& options = {},
                    const std::vector<std::uint8_t>* mask = nullptr);
// The colour of one log10 value under the false-colour scale (for plots that need the same scale).
std::array<std::uint8_t, 3> false_colour_of(double log10_value, const FalseColourOptions& options);

}  // namespace skylight::render
