// Morales et al. 2017 eqs. 7, 12-13 and 20-22 per pixel; docs/HAZE.md "Per-pixel airlight".
#include "skylight/haze/airlight_field.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "skylight/core/error.h"
#include "skylight/core/parallel.h"

namespace skylight::haze {
namespace {

std::shared_ptr<const AirlightMap> map_of(const ImagePositioning& camera,
                                          const std::function<Rgb3(Vec3)>& airlight) {
  io::ImageF out(camera.width(), camera.height(), 3);
  parallel_for(static_cast<std::size_t>(camera.height()), 4, [&](std::size_t r0, std::size_t r1) {
    for (std::size_t row = r0; row < r1; ++row)
      for (int col = 0; col < camera.width(); ++col) {
        const Rgb3 a = airlight(camera.pixel_direction(col, static_cast<int>(row)));
        float* p = out.pixel(col, static_cast<int>(row));
        for (std::size_t c = 0; c < 3; ++c) p[c] = static_cast<float>(a[c]);
      }
  });
  return std::make_shared<const AirlightMap>(std::move(out));
}

}  // namespace

AirlightTable::AirlightTable(const SkyModel& model, const CameraSensitivity& camera, double step) {
  SKYLIGHT_CHECK(step > 0.0 && step <= kPi / 4, "AirlightTable: step in (0, pi/4]");
  n_theta_ = static_cast<std::size_t>(std::ceil(kPi / 2 / step)) + 1;
  n_phi_ = static_cast<std::size_t>(std::ceil(2 * kPi / step)) + 1;
  step_theta_ = kPi / 2 / static_cast<double>(n_theta_ - 1);
  step_phi_ = 2 * kPi / static_cast<double>(n_phi_ - 1);
  values_.resize(n_theta_ * n_phi_);
  // The first exception (a model without spectral output) is rethrown by parallel_for.
  parallel_for(n_theta_, 1, [&](std::size_t i0, std::size_t i1) {
    for (std::size_t i = i0; i < i1; ++i)
      for (std::size_t j = 0; j + 1 < n_phi_; ++j)
        values_[i * n_phi_ + j] =
            sky_model_airlight(model,
                               direction_from_angles(static_cast<double>(i) * step_theta_,
                                                     static_cast<double>(j) * step_phi_),
                               camera);
  });
  for (std::size_t i = 0; i < n_theta_; ++i) values_[i * n_phi_ + n_phi_ - 1] = values_[i * n_phi_];
}

Rgb3 AirlightTable::at(Vec3 direction) const {
  const ZenithAzimuth a = angles_from_direction(direction);
  const double u = std::min(a.zenith, kPi / 2) / step_theta_;
  const double v = a.azimuth / step_phi_;
  const std::size_t i = std::min(static_cast<std::size_t>(u), n_theta_ - 2);
  const std::size_t j = std::min(static_cast<std::size_t>(v), n_phi_ - 2);
  const double fu = u - static_cast<double>(i), fv = v - static_cast<double>(j);
  const Rgb3& a00 = values_[i * n_phi_ + j];
  const Rgb3& a01 = values_[i * n_phi_ + j + 1];
  const Rgb3& a10 = values_[(i + 1) * n_phi_ + j];
  const Rgb3& a11 = values_[(i + 1) * n_phi_ + j + 1];
  Rgb3 out{};
  for (std::size_t c = 0; c < 3; ++c)
    out[c] = (1 - fu) * ((1 - fv) * a00[c] + fv * a01[c]) + fu * ((1 - fv) * a10[c] + fv * a11[c]);
  return out;
}

std::shared_ptr<const AirlightMap> photo_airlight_map(const ImagePositioning& camera,
                                                      const PhotoAirlight& horizon,
                                                      double turbidity) {
  const auto eq12 = [turbidity](const Rgb3& h, double theta_prime, double theta) {
    const double z = zeta(turbidity, theta, theta_prime);
    return Rgb3{h[0] * z, h[1] * z, h[2] * z};
  };
  const std::vector<HorizonSector>& sectors = horizon.sectors;
  if (sectors.empty())
    return map_of(camera, [&](Vec3 d) {
      return eq12(horizon.horizon, horizon.theta_prime, angles_from_direction(d).zenith);
    });
  return map_of(camera, [&](Vec3 d) {
    const ZenithAzimuth a = angles_from_direction(d);
    // The sectors on either side of phi (periodic), linear in azimuth between their centres.
    const auto next =
        std::lower_bound(sectors.begin(), sectors.end(), a.azimuth,
                         [](const HorizonSector& s, double phi) { return s.azimuth < phi; });
    const HorizonSector& hi = next == sectors.end() ? sectors.front() : *next;
    const HorizonSector& lo = next == sectors.begin() ? sectors.back() : *(next - 1);
    double span = hi.azimuth - lo.azimuth, offset = a.azimuth - lo.azimuth;
    if (span <= 0.0) span += 2 * kPi;
    if (offset < 0.0) offset += 2 * kPi;
    const double f = sectors.size() == 1 ? 0.0 : std::clamp(offset / span, 0.0, 1.0);
    const Rgb3 x = eq12(lo.horizon, lo.theta_prime, a.zenith);
    const Rgb3 y = eq12(hi.horizon, hi.theta_prime, a.zenith);
    return Rgb3{x[0] + f * (y[0] - x[0]), x[1] + f * (y[1] - x[1]), x[2] + f * (y[2] - x[2])};
  });
}

std::shared_ptr<const AirlightMap> sky_model_airlight_map(const ImagePositioning& camera,
                                                          const AirlightTable& table) {
  return map_of(camera, [&](Vec3 d) { return table.at(d); });
}

}  // namespace skylight::haze
