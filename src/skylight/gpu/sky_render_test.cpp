#include "skylight/gpu/sky_render.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "skylight/io/file.h"
#include "skylight/models/neural_sky.h"
#include "skylight/models/pietras.h"
#include "skylight/nn/pietras.h"

#include "support/gpu_context.h"

namespace skylight::gpu {
namespace {

using testing_support::GpuTest;

// GL against the CPU network (nn SkyModel batch path, render::render_sky), per pixel and
// channel, both with the CPU's float directions (DirectionSource::texture: the network alone) and
// with the directions computed in GLSL (the render path): the relative difference where the CPU
// value is above the floor (docs/GPU.md). Measured worst 2.2e-5.
constexpr double kImageRelativeTolerance = 1e-4;
// Floor: a fraction of the image's brightest channel; below it the output is "tiny" (the satilmis
// decoding 0.5 (1/y - 1) cancels as y -> 1 and absolute float rounding dominates).
constexpr double kImageRelativeFloor = 1e-3;
// Angle between the GLSL and the CPU (double) direction of a pixel [rad]: Mesa's GLSL atan is a
// polynomial approximation (measured errors up to 7e-6 rad, stereographic fisheye), the rest
// single-precision rounding of angles up to 2 pi (1e-6).
constexpr double kDirectionTolerance = 2e-5;

struct ImageDifference {
  double worst_relative = 0.0;
  int compared = 0, mask_mismatches = 0;
};

ImageDifference compare(const render::SkyImage& gpu, const render::SkyImage& cpu) {
  ImageDifference d;
  const float peak = *std::max_element(cpu.rgb.data.begin(), cpu.rgb.data.end());
  const double floor = kImageRelativeFloor * peak;
  for (std::size_t i = 0; i < cpu.mask.size(); ++i) {
    if (gpu.mask[i] != cpu.mask[i]) {
      ++d.mask_mismatches;
      continue;
    }
    for (int c = 0; c < 3; ++c) {
      const double a = gpu.rgb.data[3 * i + c], b = cpu.rgb.data[3 * i + c];
      if (std::abs(b) <= floor) continue;
      d.worst_relative = std::max(d.worst_relative, std::abs(a - b) / std::abs(b));
      ++d.compared;
    }
  }
  return d;
}

NeuralSkyParameters sky(double sun_zenith_deg, double sun_azimuth_deg) {
  NeuralSkyParameters p;
  p.sun.zenith = deg_to_rad(sun_zenith_deg);
  p.sun.azimuth = deg_to_rad(sun_azimuth_deg);
  p.turbidity = 3.5;
  return p;
}

std::vector<render::RenderSettings> layouts() {
  std::vector<render::RenderSettings> out;
  for (const auto proj : {Projection::equirect, Projection::hemisphere, Projection::fisheye,
                          Projection::cubemap, Projection::camera}) {
    render::RenderSettings s;
    s.projection = proj;
    s.width = proj == Projection::cubemap ? 192 : 160;
    s.height = proj == Projection::cubemap ? 32 : 80;
    s.pinhole.look_zenith = deg_to_rad(70.0);
    s.pinhole.look_azimuth = deg_to_rad(120.0);
    out.push_back(s);
  }
  for (const auto lens : {FisheyeLens::equidistant, FisheyeLens::equisolid,
                          FisheyeLens::orthographic, FisheyeLens::stereographic}) {
    render::RenderSettings s;
    s.projection = Projection::fisheye;
    s.width = 96;
    s.height = 96;
    s.fisheye.lens = lens;
    s.fisheye.fov = lens == FisheyeLens::orthographic ? kPi : deg_to_rad(200.0);
    s.fisheye.north_angle = deg_to_rad(30.0);
    out.push_back(s);
  }
  return out;
}

std::string name(const render::RenderSettings& s) {
  std::string n(to_string(s.projection));
  if (s.projection == Projection::fisheye) {
    n += '_';
    n += to_string(s.fisheye.lens);
  }
  return n;
}

void expect_matches_cpu(const SkyModel& model, const render::RenderSettings& s,
                        DirectionSource source, double tolerance) {
  SkyRenderer r(model, s, source);
  r.draw();
  const render::SkyImage gpu = r.image();
  const render::SkyImage cpu = render::render_sky(model, s);
  const ImageDifference d = compare(gpu, cpu);
  EXPECT_GT(d.compared, s.width * s.height) << name(s);
  EXPECT_LE(d.worst_relative, tolerance) << name(s);
  // Shader directions: a pixel centre at the very edge of a fisheye circle may fall on either
  // side in float; texture directions carry the CPU's mask.
  EXPECT_LE(d.mask_mismatches, source == DirectionSource::texture ? 0 : s.width / 8) << name(s);
  ::testing::Test::RecordProperty(
      name(s) + (source == DirectionSource::texture ? "_texture" : "_shader") + "_worst_relative",
      std::to_string(d.worst_relative));
}

TEST_F(GpuTest, NetworkMatchesTheCpuBatchPathInEveryProjection) {
  for (const double sun_zenith_deg : {40.0, 75.0}) {
    const NeuralSkyModel model(sky(sun_zenith_deg, 250.0));
    for (const auto& s : layouts())
      expect_matches_cpu(model, s, DirectionSource::texture, kImageRelativeTolerance);
  }
}

TEST_F(GpuTest, ShaderRenderMatchesTheCpuRenderInEveryProjection) {
  for (const double sun_zenith_deg : {40.0, 75.0}) {
    const NeuralSkyModel model(sky(sun_zenith_deg, 250.0));
    for (const auto& s : layouts())
      expect_matches_cpu(model, s, DirectionSource::shader, kImageRelativeTolerance);
  }
}

// Every registered model's GPU form (SkyModel::gpu_sky) against its CPU render, per pixel with
// the CPU's directions, at the registry example (each parameter of the example at its value) and
// the given suns; a model without one says why (ModelInfo::no_gpu) and returns none. Measured
// worst 1.3e-5 (hosek); the physical skies' LUT, interpolated in float on both sides, 3e-6.
// Returns the number of forms compared.
int expect_gpu_forms_match(bool costly, std::initializer_list<double> sun_zeniths_deg) {
  render::RenderSettings s;
  s.width = 96;
  s.height = 48;
  int forms = 0;
  for (const ModelInfo& info : model_registry()) {
    if (info.costly_setup != costly) continue;
    SkyParameters p;
    p.values = info.example;
    if (!info.no_gpu.empty()) {
      EXPECT_FALSE(make_sky_model(info.name, p)->gpu_sky()) << info.name;
      continue;
    }
    ++forms;
    for (const double sun_zenith_deg : sun_zeniths_deg) {
      p.sun = sun_from_degrees(sun_zenith_deg, 130.0);
      const auto model = make_sky_model(info.name, p);
      if (!model->gpu_sky()) {
        ADD_FAILURE() << info.name << " has no GPU form and no ModelInfo::no_gpu";
        continue;
      }
      expect_matches_cpu(*model, s, DirectionSource::texture, kImageRelativeTolerance);
    }
  }
  return forms;
}

TEST_F(GpuTest, EveryGpuFormMatchesItsModelsCpuRender) {
  // perez, preetham, cie, hosek, nn, pietras (nishita and sh have none)
  EXPECT_GE(expect_gpu_forms_match(false, {35.0, 80.0}), 6);
}

// The models whose set-up takes seconds (tables per atmosphere, the whole-sky LUT per sun): one
// sun each, so that the test stays under a minute under the sanitizers.
TEST_F(GpuTest, CostlyGpuFormsMatchTheirModelsCpuRender) {
  EXPECT_GE(expect_gpu_forms_match(true, {60.0}), 2);  // hillaire, bruneton
}

TEST_F(GpuTest, ShaderDirectionsMatchTheCpuLayouts) {
  for (const auto& s : layouts()) {
    const io::ImageF gpu = shader_pixel_directions(s);
    const render::PixelDirections cpu = render::pixel_directions(s);
    double worst = 0.0;
    int mismatches = 0;
    for (std::size_t i = 0; i < cpu.x.size(); ++i) {
      const float* g = gpu.data.data() + 4 * i;
      if ((g[3] != 0.0f) != (cpu.valid[i] != 0)) {
        ++mismatches;
        continue;
      }
      if (!cpu.valid[i]) continue;
      worst = std::max(worst,
                       angle_between(Vec3{g[0], g[1], g[2]}, Vec3{cpu.x[i], cpu.y[i], cpu.z[i]}));
    }
    EXPECT_LE(worst, kDirectionTolerance) << name(s);
    EXPECT_LE(mismatches, s.width / 8) << name(s);
    ::testing::Test::RecordProperty(name(s) + "_direction_worst_rad", std::to_string(worst));
  }
}

TEST_F(GpuTest, SunBelowTheHorizonIsDarkAndMaskIsKept) {
  const NeuralSkyModel model(sky(100.0, 180.0));
  render::RenderSettings s;
  s.projection = Projection::fisheye;
  s.width = 64;
  s.height = 32;
  SkyRenderer r(model, s);
  r.draw();
  const render::SkyImage img = r.image();
  EXPECT_TRUE(
      std::all_of(img.rgb.data.begin(), img.rgb.data.end(), [](float v) { return v == 0.0f; }));
  // The image circle (diameter 32) leaves the sides masked.
  EXPECT_EQ(img.mask[0], 1);
  EXPECT_EQ(img.mask[16 * 64 + 32], 0);
}

// "Tiny" in the network's own scale too: a channel below this fraction of max_value (pietras: max
// N, log3: Y_max) is not compared. There the decoding amplifies float rounding: N = max N (M -
// 0.05) / 0.9 turns M's rounding (~1e-7) into a relative error 1e-7 / (M - 0.05), 3e-3 at the
// darkest twilight pixels (measured).
constexpr double kPietrasScaleFloor = 1e-2;

// A Pietras network (the committed files, docs/PIETRAS.md) rendered per pixel by the shader
// (nn::glsl_pietras_sky) against the CPU render (PietrasBatch): the relative difference where both
// are lit and the CPU value is above the floor, and the pixels that only one side leaves dark
// (the shadow test in float against double, at the shadow's edge).
struct PietrasDifference {
  double worst_relative = 0.0;
  int compared = 0, lit_mismatches = 0, dark = 0;
};

PietrasDifference compare_pietras(const render::SkyImage& gpu, const render::SkyImage& cpu,
                                  double max_value) {
  PietrasDifference d;
  const float peak = *std::max_element(cpu.rgb.data.begin(), cpu.rgb.data.end());
  const double floor = std::max(kImageRelativeFloor * peak, kPietrasScaleFloor * max_value);
  for (std::size_t i = 0; i < cpu.mask.size(); ++i) {
    const float* a = gpu.rgb.data.data() + 3 * i;
    const float* b = cpu.rgb.data.data() + 3 * i;
    const bool gpu_dark = a[0] == 0.0f && a[1] == 0.0f && a[2] == 0.0f;
    const bool cpu_dark = b[0] == 0.0f && b[1] == 0.0f && b[2] == 0.0f;
    if (gpu_dark != cpu_dark) {
      ++d.lit_mismatches;
      continue;
    }
    if (cpu_dark) {
      ++d.dark;
      continue;
    }
    for (int c = 0; c < 3; ++c) {
      if (std::abs(b[c]) <= floor) continue;
      d.worst_relative =
          std::max(d.worst_relative, std::abs(double{a[c]} - b[c]) / std::abs(double{b[c]}));
      ++d.compared;
    }
  }
  return d;
}

// Pixels either side may leave dark alone: the shadow's edge crosses a 256 x 128 image along a
// line of a few hundred pixels, and float moves the decision by under a metre (nn/glsl.h).
constexpr int kPietrasLitMismatches = 8;

TEST_F(GpuTest, PietrasNetworksMatchTheCpuRender) {
  struct Case {
    const char* file;
    double altitude_m, sun_zenith_deg;
    bool expect_dark;  // the planet's shadow covers part of the image
  };
  const Case cases[] = {{"pietras.json", 1000.0, 40.0, false},
                        {"log3.json", 1000.0, 40.0, false},
                        {"log3.json", 15000.0, 97.0, true},
                        {"log3.json", 400e3, 80.0, true},  // space is dark: rays missing the air
                        {"pietras.json", 8000.0, 95.0, true}};
  render::RenderSettings s;
  s.projection = Projection::equirect;  // the whole sphere: views meeting the ground too
  s.width = 256;
  s.height = 128;
  for (const Case& c : cases) {
    const std::string path = std::string(SKYLIGHT_TEST_DATA_DIR) + "/nn/" + c.file;
    PietrasParameters p;
    p.observer_altitude_m = c.altitude_m;
    p.sun.zenith = deg_to_rad(c.sun_zenith_deg);
    p.sun.azimuth = deg_to_rad(150.0);
    const nn::PietrasNetwork net = nn::pietras_from_json(io::read_text_file(path), path);
    const double max_value = net.max_value;
    const PietrasSkyModel model(p, net);
    SkyRenderer r(model, s);
    r.draw();
    const PietrasDifference d = compare_pietras(r.image(), render::render_sky(model, s), max_value);
    const std::string what =
        fmt::format("{} at {} m, sun zenith {} deg", c.file, c.altitude_m, c.sun_zenith_deg);
    EXPECT_GT(d.compared, 0) << what;
    EXPECT_LE(d.worst_relative, kImageRelativeTolerance) << what;
    EXPECT_LE(d.lit_mismatches, kPietrasLitMismatches) << what;
    EXPECT_EQ(d.dark > 0, c.expect_dark) << what << ": " << d.dark << " dark pixels";
    ::testing::Test::RecordProperty(what + " worst_relative", std::to_string(d.worst_relative));
  }
}

}  // namespace
}  // namespace skylight::gpu
