// Irradiance from SH radiance coefficients: the convolution with the clamped cosine (Ramamoorthi
// & Hanrahan 2001, "An Efficient Representation for Irradiance Environment Maps", eq. 7-9), the
// diffuse lighting of Habel, Mustata & Wimmer 2008 §1.
#pragma once

#include "skylight/core/parameters.h"
#include "skylight/io/image.h"
#include "skylight/sh/projection.h"

namespace skylight::sh {

// A_l of Ramamoorthi & Hanrahan 2001 eq. 8-9: the SH coefficients of max(cos theta, 0) times
// sqrt(4 pi / (2l + 1)): A_0 = pi, A_1 = 2 pi / 3, A_l = 0 for odd l > 1,
// A_l = 2 pi (-1)^(l/2 - 1) / ((l + 2)(l - 1)) * l! / (2^l ((l/2)!)^2) for even l.
double clamped_cosine_factor(int l);

// E_lm = A_l L_lm (eq. 7): the irradiance on a surface of normal n is sum_lm E_lm Y_lm(n).
Coefficients irradiance_coefficients(const Coefficients& radiance);

// Irradiance [radiance unit x sr] on a surface with unit normal n lit by the radiance whose SH
// coefficients are given: sum_lm A_l L_lm Y_lm(n). Per channel; not clamped.
Triple irradiance(const Coefficients& radiance, Vec3 normal);

// A diffuse sphere of albedo rho under the irradiance whose SH coefficients are given
// (irradiance_coefficients of the unfiltered radiance, in `channels`), seen from the south (the
// view looks north, east to the right), its disc filling a size x size image: L = rho / pi * E(n)
// per pixel as linear sRGB (Ramamoorthi & Hanrahan 2001), 0 outside the disc.
struct SphereOptions {
  int size = 256;       // [px]
  double albedo = 0.8;  // [1]
  // --sphere-size, --sphere-albedo.
  static const ParameterSchema<SphereOptions>& schema();
};
io::ImageF diffuse_sphere(const Coefficients& irradiance, Channels channels,
                          const SphereOptions& options);

}  // namespace skylight::sh
