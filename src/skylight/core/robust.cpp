#include "skylight/core/robust.h"

#include <algorithm>
#include <limits>
#include <map>

#include "skylight/core/error.h"
#include "skylight/core/statistics.h"

namespace skylight {

void draw_distinct(SplitMix64& rng, std::size_t n, std::size_t k, std::vector<std::size_t>& out) {
  SKYLIGHT_CHECK(k <= n, "draw_distinct: more indices than there are");
  out.resize(k);
  for (std::size_t j = 0; j < k; ++j) {
    std::size_t i;
    do i = rng.below(n);
    while (std::find(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(j), i) !=
           out.begin() + static_cast<std::ptrdiff_t>(j));
    out[j] = i;
  }
}

std::vector<std::size_t> ransac(
    std::size_t n, const RansacOptions& options, SplitMix64& rng,
    const std::function<Consensus(std::span<const std::size_t>)>& trial) {
  std::vector<std::size_t> best, minimal;
  double best_ss = std::numeric_limits<double>::infinity();
  for (int it = 0; it < options.iterations; ++it) {
    draw_distinct(rng, n, options.minimal_set, minimal);
    Consensus c = trial(minimal);
    const bool more = c.inliers.size() > best.size();
    const bool tie =
        options.tie_break_by_residual && c.inliers.size() == best.size() && c.sum_squares < best_ss;
    if (more || tie) {
      best = std::move(c.inliers);
      best_ss = c.sum_squares;
    }
  }
  return best;
}

namespace {

std::vector<double> sigma_over_draws(
    int resamples, const std::function<void(std::vector<std::size_t>&)>& draw,
    const std::function<std::vector<double>(std::span<const std::size_t>)>& fit) {
  std::vector<std::vector<double>> values;
  std::vector<std::size_t> resample;
  for (int b = 0; b < resamples; ++b) {
    draw(resample);
    const std::vector<double> p = fit(resample);
    if (values.empty()) values.resize(p.size());
    SKYLIGHT_CHECK(p.size() == values.size(), "bootstrap_sigma: parameter counts differ");
    for (std::size_t k = 0; k < p.size(); ++k) values[k].push_back(p[k]);
  }
  std::vector<double> sigma;
  for (const auto& v : values) sigma.push_back(sample_standard_deviation(v));
  return sigma;
}

}  // namespace

std::vector<double> bootstrap_sigma(
    std::span<const std::size_t> indices, int resamples, SplitMix64& rng,
    const std::function<std::vector<double>(std::span<const std::size_t>)>& fit) {
  SKYLIGHT_CHECK(resamples >= 2 && !indices.empty(), "bootstrap_sigma: two draws of some indices");
  return sigma_over_draws(
      resamples,
      [&](std::vector<std::size_t>& r) {
        r.resize(indices.size());
        for (auto& i : r) i = indices[rng.below(indices.size())];
      },
      fit);
}

std::vector<double> block_bootstrap_sigma(
    std::span<const std::size_t> indices, std::span<const int> block_of, int resamples,
    SplitMix64& rng, const std::function<std::vector<double>(std::span<const std::size_t>)>& fit) {
  SKYLIGHT_CHECK(resamples >= 2 && !indices.empty(), "bootstrap_sigma: two draws of some indices");
  std::map<int, std::vector<std::size_t>> by_block;
  for (std::size_t i : indices) {
    SKYLIGHT_CHECK(i < block_of.size(), "block_bootstrap_sigma: a block per index");
    by_block[block_of[i]].push_back(i);
  }
  std::vector<const std::vector<std::size_t>*> blocks;
  for (const auto& [id, members] : by_block) blocks.push_back(&members);
  return sigma_over_draws(
      resamples,
      [&](std::vector<std::size_t>& r) {
        r.clear();
        for (std::size_t b = 0; b < blocks.size(); ++b) {
          const auto& members = *blocks[rng.below(blocks.size())];
          r.insert(r.end(), members.begin(), members.end());
        }
      },
      fit);
}

}  // namespace skylight
