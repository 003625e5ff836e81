// Sky-image sequences as training data for a neural sky model (Satilmis et al. 2016 §III-D;
// docs/NN.md): the list file (one row per image: file, optionally the sun's angles or a time, and
// a mask) and the sampled sky pixels of one image (the sun given or found, the sun's pixels and
// the non-sky pixels excluded by the sky mask of photo.h).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/core/camera.h"
#include "skylight/estimate/photo.h"
#include "skylight/io/image.h"
#include "skylight/nn/image_dataset.h"

namespace skylight::estimate {

// One row of the list. CSV with a header naming its columns, any order: `file` (required),
// `sun_zenith_deg` and `sun_azimuth_deg` (together), `time` (ISO 8601 with UTC offset; the CLI
// turns it into the sun with --lat/--lon), `mask` (a mask file for this image). Empty cells are
// absent; `#` lines and blank lines are skipped; relative paths are relative to the list's folder.
struct SequenceEntry {
  std::filesystem::path file;
  std::optional<double> sun_zenith_deg, sun_azimuth_deg;
  std::string time;  // empty: none
  std::filesystem::path mask;
  int line = 0;  // 1-based line in the list
};

// Parses the list; InvalidArgument "<where>:<line>: ..." for a malformed row (unknown column,
// missing file, one angle without the other, angles with a time, a number out of range).
std::vector<SequenceEntry> parse_sequence_list(std::string_view text, const std::string& where,
                                               const std::filesystem::path& folder);

struct SequenceSampling {
  MaskSettings mask;             // automatic rules; sun_exclusion drops the sun's pixels
  int samples_per_image = 2000;  // sky pixels drawn per image (all when the mask has fewer)
  std::uint64_t seed = 1;
};

struct SampledImage {
  nn::ImageSamples samples;
  bool sun_detected = false;   // the sun came from detect_sun
  std::size_t sky_pixels = 0;  // in the mask
};

// The sky pixels of one image: the sun (given, or found by detect_sun), the mask (automatic rules
// with the sun exclusion, within user_mask when given), then samples_per_image pixels drawn
// without replacement (SplitMix64 seeded by seed), views = the camera's pixel-centre directions,
// rgb = the pixel (a one-channel image: grey). InvalidArgument when the sun is below the horizon
// or the mask is empty.
SampledImage sample_sky_image(const io::ImageF& image, const Camera& camera,
                              const std::optional<SunPosition>& sun,
                              const SequenceSampling& sampling,
                              const io::ImageF* user_mask = nullptr);

}  // namespace skylight::estimate
