// Tone mapping of float images into 8-bit previews.
#pragma once

#include <filesystem>

#include "skylight/io/image.h"

namespace skylight::render {

using io::Image8;
using io::ImageF;
using io::Metadata;

// Linear -> 8-bit preview: scales so that the given percentile of luminance maps to `white`
// (auto exposure), applies the Reinhard operator L/(1+L) per channel ratio and the sRGB OETF.
struct ToneMapOptions {
  double percentile = 0.99;  // luminance percentile that sets the exposure, (0, 1]
  double exposure = 1.0;     // extra linear factor after auto exposure
};
Image8 tonemap_preview(const ImageF& image, const ToneMapOptions& options = {});

// Writes `image` to `path` by extension: .exr/.hdr/.pfm as float data (io::write_image), .png as
// the tone-mapped preview (tonemap_preview with default options) with the metadata as text chunks.
void write_image_or_preview(const std::filesystem::path& path, const ImageF& image,
                            const Metadata& meta = {});

}  // namespace skylight::render
