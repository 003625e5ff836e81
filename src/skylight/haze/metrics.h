// Image similarity measures of Morales et al. 2017 §7.2.3: SSIM (Wang, Bovik, Sheikh & Simoncelli
// 2004) and the HSV histogram correlation (eq. 27); docs/HAZE.md.
#pragma once

#include "skylight/io/image.h"

namespace skylight::haze {

struct SsimSettings {
  double dynamic_range = 1.0;   // L [image units]: the range of the values (1 for [0, 1] images)
  double k1 = 0.01, k2 = 0.03;  // C1 = (K1 L)^2, C2 = (K2 L)^2 (Wang et al. 2004, eq. 13)
  double sigma = 1.5;           // the Gaussian window's sigma [pixels]
  int window = 11;              // its width (odd)
};

// The mean SSIM (Wang et al. 2004 eqs. 13 and 17): the SSIM map over every position where the
// 11 x 11 Gaussian window (normalised to sum 1) lies inside the image, averaged, then averaged
// over the channels. Images of the same size and channel count, at least the window's size;
// InvalidArgument otherwise.
double ssim(const io::ImageF& a, const io::ImageF& b, const SsimSettings& settings = {});

// Bins of the HSV histograms: hue [0, 360) deg, saturation and value [0, 1].
struct HsvHistogramSettings {
  int hue_bins = 50, saturation_bins = 60, value_bins = 60;
};

// Eq. 27 per channel c in {H, S, V}: the correlation of the two images' histograms
//   sum (H1 - mean H1)(H2 - mean H2) / sqrt(sum (H1 - mean H1)^2 sum (H2 - mean H2)^2)
// (the square root over the product of the two sums, as the correlation coefficient; the printed
// equation drops the sums), averaged over H, S and V. RGB values are clamped to [0, 1] before the
// conversion. Two constant histograms correlate 1 if equal, else 0.
double hsv_histogram_correlation(const io::ImageF& a, const io::ImageF& b,
                                 const HsvHistogramSettings& settings = {});

}  // namespace skylight::haze
