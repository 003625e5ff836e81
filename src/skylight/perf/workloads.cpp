#include "skylight/perf/workloads.h"

#include <time.h>

#include <algorithm>
#include <chrono>

#include "skylight/core/math.h"
#include "skylight/core/parallel.h"
#include "skylight/core/statistics.h"
#include "skylight/fit/sh_fit.h"
#include "skylight/haze/airlight_field.h"
#include "skylight/haze/positioning.h"
#include "skylight/models/pietras.h"
#include "skylight/models/preetham.h"

namespace skylight::perf {

std::unique_ptr<SkyModel> bench_model(std::string_view name) {
  const ModelInfo* info = find_model(name);
  SKYLIGHT_CHECK(info != nullptr, "bench_model: a registered model");
  SkyParameters p;
  p.values = info->example;
  return info->make(p);
}

std::vector<std::string> default_bench_models() {
  std::vector<std::string> out;
  for (const auto& m : model_registry())
    if (m.bench.by_default) out.push_back(m.name);
  return out;
}

DirectionGrid::DirectionGrid(int width, int height) {
  render::RenderSettings s;
  s.width = width;
  s.height = height;
  d = render::pixel_directions(s);
  X.resize(d.x.size());
  Y.resize(d.x.size());
  Z.resize(d.x.size());
}

void DirectionGrid::scalar(const SkyModel& model) {
  for (std::size_t i = 0; i < size(); ++i)
    Y[i] = static_cast<float>(model.tristimulus({d.x[i], d.y[i], d.z[i]}).Y);
}

void DirectionGrid::batch(const SkyModel& model) {
  model.tristimulus_batch({d.x, d.y, d.z}, {X, Y, Z});
}

void DirectionGrid::threads(const SkyModel& model) {
  tristimulus_parallel(model, {d.x, d.y, d.z}, {X, Y, Z});
}

EstimatePhoto estimate_photo() {
  render::RenderSettings s;
  s.projection = Projection::fisheye;
  s.width = s.height = 1024;
  s.sun = SunMode::sky_and_sun;
  PreethamParameters p;
  p.sun = {deg_to_rad(40.0), deg_to_rad(150.0)};
  p.turbidity = 4.0;
  return {render::render_sky(PreethamModel(p), s).rgb,
          Camera{Projection::fisheye, 1024, 1024, {}, {}}};
}

fit::PhotoFit estimate_once(const EstimatePhoto& photo) {
  return fit::estimate_from_photo(PreethamModel::kName, photo.photo, photo.camera, std::nullopt, {},
                                  {});
}

HazeFrame::HazeFrame(int height) : image(1920, height, 3), depth(1920, height, 1) {
  for (std::size_t i = 0; i < depth.data.size(); ++i) {
    depth.data[i] = 100.0f + 19900.0f * static_cast<float>(i / 1920) / static_cast<float>(height);
    for (std::size_t c = 0; c < 3; ++c)
      image.data[3 * i + c] = 0.2f + 0.6f * static_cast<float>((i * (c + 3)) % 97) / 97.0f;
  }
  settings.operation = haze::HazeOperation::retarget;
  settings.source = {1.9, 40.0};
  settings.target_turbidity = 4.36;
}

const haze::CameraSensitivity& haze_camera() {
  return haze::find_camera("canon-eos-5d");
}

void add_per_pixel_airlight(HazeFrame& frame) {
  const haze::ImagePositioning pinhole(
      haze::view_matrix(3.0, 0.05, 0.0),
      haze::perspective_matrix(60.0 * kDegree, 1920.0 / 1080.0, 1.0, 1e4), 1920, 1080);
  haze::PhotoAirlight horizon;
  horizon.horizon = {0.7, 0.8, 0.95};
  horizon.theta_prime = 80.0 * kDegree;
  frame.settings.airlight_source_map = haze::photo_airlight_map(pinhole, horizon, 1.9);
  frame.settings.airlight_target_map = haze::photo_airlight_map(pinhole, horizon, 4.36);
}

sh::Coefficients evaluate_sh_table(const sh::PolynomialTable& table, double theta) {
  const double tau = std::clamp(3.0, table.tau_min, table.tau_max);
  return sh::evaluate_table(table, theta, tau, 0.5 + theta, 7, true);
}

sh::Projection project_sh_model(const sh::PolynomialTable& table) {
  const double tau = std::clamp(3.0, table.tau_min, table.tau_max);
  return fit::project_reference(table, 0.8, tau, 0.5, 7);
}

std::unique_ptr<SkyModel> pietras_bench_model(nn::PietrasKind kind) {
  PietrasParameters p;
  p.sun = {deg_to_rad(45.0), kPi};
  return std::make_unique<PietrasSkyModel>(p, nn::initial_pietras_network(kind, 1));
}

double median_seconds(int repeats, const std::function<void()>& f) {
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    const auto a = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count());
  }
  return median(std::move(t));
}

}  // namespace skylight::perf
