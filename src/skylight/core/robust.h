// Robust fitting machinery shared by the fits of sky models to photos (fit/): RANSAC (Fischler &
// Bolles 1981) over minimal sets of samples and the bootstrap (Efron 1979) spread of a fit's
// parameters. Both draw from the project's SplitMix64, so a seed fixes every result.
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "skylight/core/random.h"

namespace skylight {

// `k` distinct indices of [0, n) (k <= n) drawn with `rng` into `out` (resized to k).
void draw_distinct(SplitMix64& rng, std::size_t n, std::size_t k, std::vector<std::size_t>& out);

// The samples that agree with a trial fit, and the sum of their squared residuals.
struct Consensus {
  std::vector<std::size_t> inliers;
  double sum_squares = 0.0;
};

struct RansacOptions {
  int iterations = 64;                // minimal sets tried
  std::size_t minimal_set = 3;        // samples per minimal set
  bool tie_break_by_residual = true;  // equal inlier counts: the smaller sum of squares wins
};

// `options.iterations` minimal sets of distinct indices of [0, n), each passed to `trial` (which
// fits them and returns the consensus of that fit over all n samples); returns the best
// consensus: the most inliers (ties: see RansacOptions), empty if every consensus was.
std::vector<std::size_t> ransac(
    std::size_t n, const RansacOptions& options, SplitMix64& rng,
    const std::function<Consensus(std::span<const std::size_t>)>& trial);

// `resamples` bootstrap draws of |indices| indices with replacement from `indices`, each passed to
// `fit` (which returns the fitted parameters); the sample standard deviation of each parameter
// over the draws. resamples >= 2.
std::vector<double> bootstrap_sigma(
    std::span<const std::size_t> indices, int resamples, SplitMix64& rng,
    const std::function<std::vector<double>(std::span<const std::size_t>)>& fit);

// The block bootstrap (Kuensch 1989): the indices grouped by block_of[index] (errors correlated
// within a block, independent between blocks); each draw takes as many blocks as there are, with
// replacement, and all their indices. With one index per block it is bootstrap_sigma.
std::vector<double> block_bootstrap_sigma(
    std::span<const std::size_t> indices, std::span<const int> block_of, int resamples,
    SplitMix64& rng, const std::function<std::vector<double>(std::span<const std::size_t>)>& fit);

}  // namespace skylight
