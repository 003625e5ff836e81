// Log-luminance false-colour maps with a legend bar (after Zotti, Wilkie & Purgathofer 2007).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "skylight/core/parameters.h"
#include "skylight/io/image.h"

namespace skylight::render {

using io::Image8;
using io::ImageF;

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

  // --false-colour-range LO,HI [log10 cd/m^2] (LO below HI).
  static const ParameterSchema<FalseColourOptions>& schema();
};
Image8 false_colour(const ImageF& luminance, const FalseColourOptions& options = {},
                    const std::vector<std::uint8_t>* mask = nullptr);
// The colour of one log10 value under the false-colour scale (for plots that need the same scale).
std::array<std::uint8_t, 3> false_colour_of(double log10_value, const FalseColourOptions& options);

}  // namespace skylight::render
