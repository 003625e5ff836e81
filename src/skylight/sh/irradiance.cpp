#include "skylight/sh/irradiance.h"

#include <cmath>

#include "skylight/core/colorimetry.h"
#include "skylight/core/math.h"
#include "skylight/sh/basis.h"
#include "skylight/sh/rotation.h"

namespace skylight::sh {

double clamped_cosine_factor(int l) {
  if (l == 0) return kPi;
  if (l == 1) return 2.0 * kPi / 3.0;
  if (l % 2 == 1) return 0.0;
  // l! / (2^l ((l/2)!)^2) = C(l, l/2) / 2^l, built as a product to stay exact in double.
  double ratio = 1.0;
  for (int k = 1; k <= l / 2; ++k) ratio *= static_cast<double>(l / 2 + k) / (4.0 * k);
  const double sign = (l / 2 - 1) % 2 == 0 ? 1.0 : -1.0;
  return 2.0 * kPi * sign / ((l + 2.0) * (l - 1.0)) * ratio;
}

Coefficients irradiance_coefficients(const Coefficients& radiance) {
  Coefficients e = radiance;
  for (std::size_t i = 0; i < e.c.size(); ++i) {
    const double a = clamped_cosine_factor(degree_order(static_cast<int>(i)).l);
    for (double& v : e.c[i]) v *= a;
  }
  return e;
}

Triple irradiance(const Coefficients& radiance, Vec3 normal) {
  return reconstruct(irradiance_coefficients(radiance), normal);
}

const ParameterSchema<SphereOptions>& SphereOptions::schema() {
  static const ParameterSchema<SphereOptions> s = [] {
    const SphereOptions d;
    ParameterSchema<SphereOptions> s;
    s.integer(&SphereOptions::size, {.name = "sphere-size",
                                     .unit = "px",
                                     .kind = ParameterKind::integer,
                                     .min = 2,
                                     .max = 8192,
                                     .default_value = ParameterValue(static_cast<double>(d.size)),
                                     .description = "sphere image side"})
        .number(&SphereOptions::albedo, {.name = "sphere-albedo",
                                         .unit = "1",
                                         .min = 0,
                                         .max = 1,
                                         .default_value = ParameterValue(d.albedo),
                                         .description = "diffuse albedo of the sphere"});
    return s;
  }();
  return s;
}

io::ImageF diffuse_sphere(const Coefficients& irradiance, Channels channels,
                          const SphereOptions& options) {
  const Coefficients& e = irradiance;
  const int size = options.size;
  io::ImageF img(size, size, 3);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const double u = (2.0 * (x + 0.5) / size) - 1.0, v = 1.0 - (2.0 * (y + 0.5) / size);
      const double r2 = u * u + v * v;
      if (r2 > 1.0) continue;
      const Triple t = reconstruct(e, Vec3{u, -std::sqrt(1.0 - r2), v});
      const Xyz xyz = channels == Channels::xyz ? Xyz{t[0], t[1], t[2]}
                                                : linear_srgb_to_xyz({t[0], t[1], t[2]});
      const Rgb rgb = xyz_to_linear_srgb(xyz);
      float* p = img.pixel(x, y);
      p[0] = static_cast<float>(options.albedo / kPi * rgb.r);
      p[1] = static_cast<float>(options.albedo / kPi * rgb.g);
      p[2] = static_cast<float>(options.albedo / kPi * rgb.b);
    }
  }
  return img;
}

}  // namespace skylight::sh
