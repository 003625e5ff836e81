#include "skylight/gpu/haze.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "skylight/core/error.h"
#include "skylight/haze/airlight_field.h"
#include "support/gpu_context.h"

namespace skylight::gpu {
namespace {

using testing_support::GpuTest;

// The shader runs the CPU kernel's float arithmetic on the same float tables (haze::HazeKernel);
// the CPU's SIMD kernel may fuse multiply-adds and a driver may too, or divide approximately:
// each of the ~6 operations moves by an ulp, times the 1 / min transmission = 20 amplification of
// remove: 1e-5 of (1 + |I_out|) bounds that (measured worst 4.5e-7 on llvmpipe, docs/GPU.md).
constexpr double kGpuHazeTolerance = 1e-5;
// Normalised depth (eq. 19) converted in float by the shader against double on the CPU: the depth
// moves by a few float ulp, Gamma by beta s times that (measured worst 2.5e-7 on llvmpipe).
constexpr double kGpuNormalisedTolerance = 2e-6;

const haze::CameraSensitivity& eos() {
  return haze::find_camera("canon-eos-5d");
}

// RGB in [0.05, 0.95] with edges, and a depth ramp from `near` (bottom) to `far` (top) with a
// diagonal ripple so that neighbouring pixels fall in different table intervals.
io::ImageF pattern(int w, int h) {
  io::ImageF im(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = im.pixel(x, y);
      p[0] = 0.05f + 0.9f * static_cast<float>(x) / static_cast<float>(w - 1);
      p[1] = ((x / 8) + (y / 8)) % 2 == 0 ? 0.8f : 0.2f;
      p[2] = 0.05f + 0.9f * static_cast<float>(y) / static_cast<float>(h - 1);
    }
  return im;
}

io::ImageF ramp(int w, int h, float near, float far) {
  io::ImageF d(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float t = static_cast<float>(y) / static_cast<float>(h - 1);
      const float ripple = 0.01f * static_cast<float>((x * 7 + y * 3) % 11);
      d.pixel(x, y)[0] = std::min(far, far + (near - far) * t + ripple * (far - near));
    }
  return d;
}

haze::HazeSettings settings(haze::HazeOperation op, double t,
                            std::optional<double> target = std::nullopt) {
  haze::HazeSettings s;
  s.operation = op;
  s.source = haze::Atmosphere{t, 40.0, haze::ScatteringVariant::improved};
  s.target_turbidity = target;
  s.airlight_source = {0.7, 0.8, 0.95};
  s.airlight_target = {0.75, 0.8, 0.9};
  return s;
}

// A w x h pinhole camera (heading, pitch, roll [rad], vertical field of view `vfov_deg`) for the
// per-pixel airlights.
haze::ImagePositioning pinhole(int w, int h, double heading, double pitch, double roll,
                               double vfov_deg) {
  return haze::ImagePositioning(
      haze::view_matrix(heading, pitch, roll),
      haze::perspective_matrix(vfov_deg * kDegree, static_cast<double>(w) / h, 1.0, 1e4), w, h);
}

// A sky photo's horizon region: its brightest pixels' mean colour (0.7, 0.8, 0.95) at a mean
// zenith angle of `theta_prime_deg`.
haze::PhotoAirlight horizon_airlight(double theta_prime_deg) {
  haze::PhotoAirlight horizon;
  horizon.horizon = {0.7, 0.8, 0.95};
  horizon.theta_prime = theta_prime_deg * kDegree;
  return horizon;
}

// The largest |gpu - cpu| / (1 + |cpu|) over every pixel and channel.
double worst_difference(const io::ImageF& gpu, const io::ImageF& cpu) {
  EXPECT_EQ(gpu.width, cpu.width);
  EXPECT_EQ(gpu.height, cpu.height);
  EXPECT_EQ(gpu.channels, 3);
  double worst = 0.0;
  for (std::size_t i = 0; i < cpu.data.size(); ++i) {
    EXPECT_TRUE(std::isfinite(gpu.data[i]));
    worst = std::max(worst, std::abs(static_cast<double>(gpu.data[i]) - cpu.data[i]) /
                                (1.0 + std::abs(cpu.data[i])));
  }
  return worst;
}

TEST_F(GpuTest, HazeMatchesTheCpuKernelPerPixel) {
  const int w = 64, h = 48;
  const io::ImageF image = pattern(w, h);
  struct Case {
    const char* name;
    haze::HazeSettings s;
    float far_m;
  };
  // Remove at T 8 over 30 km and retarget 8 -> 2 reach the transmission floor.
  const Case cases[] = {
      {"add T 4", settings(haze::HazeOperation::add, 4.0), 20000.0f},
      {"retarget 2 -> 6", settings(haze::HazeOperation::retarget, 2.0, 6.0), 20000.0f},
      {"retarget 8 -> 2", settings(haze::HazeOperation::retarget, 8.0, 2.0), 30000.0f},
      {"remove T 8", settings(haze::HazeOperation::remove, 8.0), 30000.0f},
  };
  for (const Case& c : cases) {
    const io::ImageF depth = ramp(w, h, 50.0f, c.far_m);
    haze::HazeReport cpu_report, gpu_report;
    const io::ImageF cpu = haze::apply_haze(image, depth, eos(), c.s, &cpu_report);
    HazeRenderer r(w, h, c.s.operation, {});
    const io::ImageF gpu = r.apply(image, depth, eos(), c.s, &gpu_report);
    const double worst = worst_difference(gpu, cpu);
    std::cout << "[ haze gpu ] " << c.name << ": worst |gpu - cpu| / (1 + |cpu|) = " << worst
              << ", " << gpu_report.table_entries << " table entries, "
              << gpu_report.clamped_transmission_pixels << " pixels at the floor\n";
    EXPECT_LE(worst, kGpuHazeTolerance) << c.name;
    EXPECT_EQ(gpu_report.table_entries, cpu_report.table_entries) << c.name;
    EXPECT_EQ(gpu_report.table_error_bound, cpu_report.table_error_bound) << c.name;
    EXPECT_EQ(gpu_report.clamped_transmission_pixels, cpu_report.clamped_transmission_pixels)
        << c.name;
  }
  // The floor is reached where the cases say it is.
  haze::HazeReport report;
  HazeRenderer r(w, h, haze::HazeOperation::remove, {});
  r.apply(image, ramp(w, h, 50.0f, 30000.0f), eos(), settings(haze::HazeOperation::remove, 8.0),
          &report);
  EXPECT_GT(report.clamped_transmission_pixels, 0u);
}

TEST_F(GpuTest, HazeTablesLongerThanATextureRowMatch) {
  // A 1e-9 table error needs thousands of entries: several texture rows (gpu/haze.cpp).
  const int w = 32, h = 24;
  haze::HazeSettings s = settings(haze::HazeOperation::retarget, 3.0, 7.0);
  s.table_error = 1e-9;
  const io::ImageF image = pattern(w, h), depth = ramp(w, h, 10.0f, 15000.0f);
  haze::HazeReport report;
  const io::ImageF cpu = haze::apply_haze(image, depth, eos(), s, &report);
  ASSERT_GT(report.table_entries, 2048u);
  HazeRenderer r(w, h, s.operation, {});
  EXPECT_LE(worst_difference(r.apply(image, depth, eos(), s), cpu), kGpuHazeTolerance);
}

TEST_F(GpuTest, HazeNormalisedDepthMatchesEquation19OnTheCpu) {
  const int w = 64, h = 48;
  const haze::DepthEncoding enc{10.0, 8000.0};
  io::ImageF s_bar(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      s_bar.pixel(x, y)[0] = static_cast<float>(x + w * y) / static_cast<float>(w * h - 1);
  const io::ImageF image = pattern(w, h);
  const io::ImageF metres = haze::depth_in_metres(s_bar, enc, w, h, "depth");
  for (const haze::HazeSettings& s : {settings(haze::HazeOperation::add, 5.0),
                                      settings(haze::HazeOperation::retarget, 6.0, 2.5)}) {
    const io::ImageF cpu = haze::apply_haze(image, metres, eos(), s);
    HazeRenderer r(w, h, s.operation, enc);
    const double worst = worst_difference(r.apply(image, s_bar, eos(), s), cpu);
    std::cout << "[ haze gpu ] normalised depth: worst " << worst << "\n";
    EXPECT_LE(worst, kGpuNormalisedTolerance);
  }
}

TEST_F(GpuTest, HazeChecksItsInputsAsTheCpuPathDoes) {
  const io::ImageF image = pattern(8, 6);
  io::ImageF depth = ramp(8, 6, 10.0f, 100.0f);
  depth.pixel(3, 2)[0] = -1.0f;
  const haze::HazeSettings s = settings(haze::HazeOperation::add, 3.0);
  try {
    apply_haze(image, depth, {}, eos(), s);
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "the depth map pixel (3, 2) is -1; depth must be finite and >= 0 m");
  }
  EXPECT_THROW(apply_haze(image, ramp(8, 6, 0.2f, 0.9f), {10.0, 5.0}, eos(), s), InvalidArgument);
  EXPECT_THROW(apply_haze(image, ramp(8, 5, 10.0f, 100.0f), {}, eos(), s), InvalidArgument);
  haze::HazeSettings no_target = settings(haze::HazeOperation::retarget, 3.0);
  EXPECT_THROW(apply_haze(image, ramp(8, 6, 10.0f, 100.0f), {}, eos(), no_target), InvalidArgument);
  // Add reads no Gamma_s table, remove no Gamma_t table.
  EXPECT_EQ(haze_fragment_source(haze::HazeOperation::add, false).find("skylight_gamma_s"),
            std::string::npos);
  EXPECT_EQ(haze_fragment_source(haze::HazeOperation::remove, false).find("skylight_gamma_t"),
            std::string::npos);
}

// Per-pixel airlights (eqs. 12-13 through a pinhole camera, haze/airlight_field.h) as textures
// against the CPU kernel's maps.
TEST_F(GpuTest, HazePerPixelAirlightMatchesTheCpuKernel) {
  const int w = 48, h = 32;
  const haze::ImagePositioning camera = pinhole(w, h, 0.8, 0.05, 0.1, 40.0);
  const haze::PhotoAirlight horizon = horizon_airlight(80.0);
  const io::ImageF image = pattern(w, h), depth = ramp(w, h, 50.0f, 25000.0f);
  for (const haze::HazeOperation op :
       {haze::HazeOperation::add, haze::HazeOperation::retarget, haze::HazeOperation::remove}) {
    haze::HazeSettings s = settings(
        op, 3.0, op == haze::HazeOperation::retarget ? std::optional<double>(6.0) : std::nullopt);
    s.airlight_source_map = haze::photo_airlight_map(camera, horizon, 3.0);
    if (op == haze::HazeOperation::retarget)
      s.airlight_target_map = haze::photo_airlight_map(camera, horizon, 6.0);
    const io::ImageF cpu = haze::apply_haze(image, depth, eos(), s);
    HazeRenderer r(w, h, op, {}, true);
    const double worst = worst_difference(r.apply(image, depth, eos(), s), cpu);
    std::cout << "[ haze gpu ] per-pixel airlight, operation " << static_cast<int>(op)
              << ": worst |gpu - cpu| / (1 + |cpu|) = " << worst << "\n";
    EXPECT_LE(worst, kGpuHazeTolerance);
  }
}

TEST_F(GpuTest, CompositeMatchesTheCpuComposite) {
  // A partly covering object (alpha ramps 0 .. 1 across, 0 in the left quarter, where its depth is
  // 0 too) at 200 m .. 25 km over a background; T 3 and T 7.
  const int w = 64, h = 48;
  const io::ImageF background = pattern(w, h);
  io::ImageF object(w, h, 3), alpha(w, h, 1), depth = ramp(w, h, 200.0f, 25000.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float a = x < w / 4 ? 0.0f : static_cast<float>(x - w / 4) / (w - 1 - w / 4);
      alpha.pixel(x, y)[0] = a;
      if (a == 0.0f) depth.pixel(x, y)[0] = 0.0f;
      for (int c = 0; c < 3; ++c)
        object.pixel(x, y)[c] = 0.1f + 0.2f * static_cast<float>(c) + 0.01f * ((x + y) % 7);
    }
  for (double t : {3.0, 7.0}) {
    const haze::HazeSettings s = settings(haze::HazeOperation::add, t);
    const io::ImageF cpu = haze::composite(background, object, alpha, depth, eos(), s);
    const io::ImageF on_gl = gpu::composite(background, object, alpha, depth, eos(), s);
    const double worst = worst_difference(on_gl, cpu);
    std::cout << "[ haze gpu ] composite T " << t << ": worst |gpu - cpu| / (1 + |cpu|) = " << worst
              << "\n";
    EXPECT_LE(worst, kGpuHazeTolerance);
    // Uncovered pixels are the background.
    for (int c = 0; c < 3; ++c) EXPECT_EQ(on_gl.pixel(2, 5)[c], background.pixel(2, 5)[c]);
  }
  // Per-pixel airlight (eqs. 12-13 through a pinhole, haze/airlight_field.h) as a texture.
  const haze::ImagePositioning camera = pinhole(w, h, 2.0, 0.02, 0.0, 50.0);
  haze::PhotoAirlight horizon = horizon_airlight(82.0);
  horizon.sectors = {haze::HorizonSector{1.5, {0.5, 0.7, 0.9}, 84.0 * kDegree, 1},
                     haze::HorizonSector{2.5, {0.9, 0.8, 0.6}, 86.0 * kDegree, 1}};
  haze::HazeSettings per_pixel = settings(haze::HazeOperation::add, 4.0);
  per_pixel.airlight_source_map = haze::photo_airlight_map(camera, horizon, 4.0);
  const io::ImageF cpu = haze::composite(background, object, alpha, depth, eos(), per_pixel);
  const double worst =
      worst_difference(gpu::composite(background, object, alpha, depth, eos(), per_pixel), cpu);
  std::cout << "[ haze gpu ] composite, per-pixel airlight: worst |gpu - cpu| / (1 + |cpu|) = "
            << worst << "\n";
  EXPECT_LE(worst, kGpuHazeTolerance);
  // The CPU path's checks.
  io::ImageF bad_alpha = alpha;
  bad_alpha.pixel(30, 3)[0] = 1.5f;
  const haze::HazeSettings s = settings(haze::HazeOperation::add, 3.0);
  EXPECT_THROW(gpu::composite(background, object, bad_alpha, depth, eos(), s), InvalidArgument);
  EXPECT_THROW(gpu::composite(background, pattern(w, h - 1), alpha, depth, eos(), s),
               InvalidArgument);
  io::ImageF bad_depth = depth;
  bad_depth.pixel(40, 3)[0] = -2.0f;
  EXPECT_THROW(gpu::composite(background, object, alpha, bad_depth, eos(), s), InvalidArgument);
}

}  // namespace
}  // namespace skylight::gpu
