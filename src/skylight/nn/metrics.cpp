#include "skylight/nn/metrics.h"

#include <algorithm>
#include <cmath>

#include "skylight/core/error.h"
#include "skylight/core/parallel.h"
#include "skylight/core/statistics.h"

namespace skylight::nn {

ErrorStats evaluate_errors(const SkyNetwork& sky, const Dataset& ds) {
  const std::size_t n = ds.size();
  const int n_in = ds.n_inputs();
  SKYLIGHT_CHECK(sky.net.layout().inputs() == n_in && sky.inputs == ds.input_spec,
                 "evaluate_errors: the network's inputs differ from the dataset's");
  std::vector<double> net_L(3 * n);
  parallel_for(n, 1024, [&](std::size_t b, std::size_t e) {
    std::vector<double> y(3);
    for (std::size_t i = b; i < e; ++i) {
      sky.net.forward(std::span<const double>(ds.inputs).subspan(i * n_in, n_in), y);
      for (int c = 0; c < 3; ++c) net_L[3 * i + c] = sky.radiance(y[c]);
    }
  });
  ErrorStats s;
  s.samples = 3 * n;
  double sum2 = 0.0, rel_sum = 0.0;
  std::vector<double> rel;
  rel.reserve(3 * n);
  for (std::size_t k = 0; k < 3 * n; ++k) {
    const double L = ds.radiance[k], Ln = net_L[k];
    const double r = encode_radiance(OutputEncoding::satilmis, Ln) -
                     encode_radiance(OutputEncoding::satilmis, L);
    sum2 += r * r;
    if (L >= kRelativeErrorFloor) {
      const double e = std::abs(Ln - L) / L;
      rel.push_back(e);
      rel_sum += e;
      s.relative_max = std::max(s.relative_max, e);
    } else {
      ++s.relative_excluded;
    }
  }
  s.rmse = std::sqrt(sum2 / static_cast<double>(3 * n));
  s.relative_count = rel.size();
  if (!rel.empty()) {
    s.relative_mean = rel_sum / static_cast<double>(rel.size());
    s.relative_median = nearest_rank_percentile(rel, 0.5);
    s.relative_p95 = nearest_rank_percentile(rel, 0.95);
  }
  return s;
}

IrradianceStats evaluate_irradiance(const SkyNetwork& sky, const Dataset& ds,
                                    const SkySource& source, int n_theta, int n_phi) {
  IrradianceStats st;
  const std::size_t ns = ds.states.size();
  st.reference.resize(ns);
  st.network.resize(ns);
  const double dt = (kPi / 2) / n_theta, dp = (2 * kPi) / n_phi;
  parallel_for(ns, 1, [&](std::size_t b, std::size_t e) {
    for (std::size_t si = b; si < e; ++si) {
      const SkyState& s = ds.states[si];
      const SkyFunction model = source(s);
      std::array<double, 3> ir{}, in{};
      for (int it = 0; it < n_theta; ++it) {
        const double theta = (it + 0.5) * dt;
        const double w = std::cos(theta) * std::sin(theta) * dt * dp;  // cos theta d omega
        for (int ip = 0; ip < n_phi; ++ip) {
          const Vec3 v = direction_from_angles(theta, (ip + 0.5) * dp);
          const Rgb c = model(v);
          const Rgb cn = sky.rgb(s, v);
          ir[0] += w * c.r;
          ir[1] += w * c.g;
          ir[2] += w * c.b;
          in[0] += w * cn.r;
          in[1] += w * cn.g;
          in[2] += w * cn.b;
        }
      }
      for (int c = 0; c < 3; ++c) {
        st.reference[si][c] = ir[c] / ds.spec.target_scale;
        st.network[si][c] = in[c] / sky.target_scale;
      }
    }
  });
  for (std::size_t si = 0; si < ns; ++si) {
    for (int c = 0; c < 3; ++c) {
      const double r = st.reference[si][c], m = st.network[si][c];
      st.reference_mean += r;
      st.network_mean += m;
      st.abs_difference_mean += std::abs(m - r);
      const double rel = r > 0.0 ? std::abs(m - r) / r : 0.0;
      st.rel_difference_mean += rel;
      st.rel_difference_max = std::max(st.rel_difference_max, rel);
    }
  }
  const double count = 3.0 * static_cast<double>(ns);
  st.reference_mean /= count;
  st.network_mean /= count;
  st.abs_difference_mean /= count;
  st.rel_difference_mean /= count;
  return st;
}

}  // namespace skylight::nn
