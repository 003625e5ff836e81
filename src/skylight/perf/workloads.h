// The benchmarks' workloads, one list for both front ends: `skylight bench` times them against
// in-run baselines and prints ratios (perf/bench.h), Google Benchmark times the same bodies
// (bench/bench_models.cpp). Timing is never tested (docs/ARCHITECTURE.md, "Testing").
#pragma once

#include <functional>
#include <memory>
#include <string_view>
#include <utility>
#include <vector>

#include "skylight/core/camera.h"
#include "skylight/fit/luminance_fit.h"
#include "skylight/haze/image_haze.h"
#include "skylight/haze/sensitivity.h"
#include "skylight/io/image.h"
#include "skylight/models/sky_model.h"
#include "skylight/nn/pietras.h"
#include "skylight/render/sky_render.h"
#include "skylight/sh/polynomial.h"

namespace skylight::perf {

// Every benchmarked sky: the model at its defaults plus the registry's example values for the
// required parameters (T = 3, albedo 0.3, CIE type 12, ...), the sun at zenith 45 deg, azimuth
// 180 deg (SkyParameters' defaults).
std::unique_ptr<SkyModel> bench_model(std::string_view name);
// The models a model's BenchPolicy compares it with and `skylight bench` times by default.
std::vector<std::string> default_bench_models();

// Directions of a width x height equirect grid and XYZ buffers for one batch.
struct DirectionGrid {
  explicit DirectionGrid(int width = 1024, int height = 512);
  render::PixelDirections d;
  std::vector<float> X, Y, Z;
  std::size_t size() const { return d.x.size(); }
  // The plain scalar loop (double, virtual call): the in-run baseline.
  void scalar(const SkyModel& model);
  // The SIMD float batch on the calling thread.
  void batch(const SkyModel& model);
  // The batch over all threads (parallel_for chunks).
  void threads(const SkyModel& model);
};

// The photo of the estimate benchmark: a 1024 x 1024 equidistant fisheye Preetham sky (T = 4, sun
// at 40 deg zenith / 150 deg azimuth) with the solar disc, as `render` draws it.
struct EstimatePhoto {
  io::ImageF photo;
  Camera camera;
};
EstimatePhoto estimate_photo();
// One `skylight estimate` of it (sun detection, automatic mask, 100 samples, RANSAC, bootstrap)
// on the calling thread.
fit::PhotoFit estimate_once(const EstimatePhoto& photo);

// Morales 2017 eq. 26 on a 1920 x height frame + depth (100 m .. 20 km), T 1.9 -> 4.36.
struct HazeFrame {
  explicit HazeFrame(int height = 1080);
  io::ImageF image, depth;
  haze::HazeSettings settings;
};
// The camera of the haze benchmarks (Canon EOS 5D).
const haze::CameraSensitivity& haze_camera();
// The settings with per-pixel airlight at both turbidities (eqs. 12-13 through a 60 deg pinhole,
// haze/airlight_field.h).
void add_per_pixel_airlight(HazeFrame& frame);

// Habel 2008 §4: the 7 bands x 3 channels of one sky from a table (eq. 1, rotation eq. 4,
// ringing filter eq. 5) at sun zenith theta; and the converged projection of the table's model
// that it replaces.
sh::Coefficients evaluate_sh_table(const sh::PolynomialTable& table, double theta);
sh::Projection project_sh_model(const sh::PolynomialTable& table);

// The pietras model with a network of each kind (the trainer's initial weights: the cost of a
// trained network), the sun at zenith 45 deg on the ground.
std::unique_ptr<SkyModel> pietras_bench_model(nn::PietrasKind kind);

// Timing: the median wall time of `repeats` runs of f [s]; this thread's and this process's CPU
// time [s].
double median_seconds(int repeats, const std::function<void()>& f);

}  // namespace skylight::perf
