#include "skylight/estimate/sky_sequence.h"

#include <gtest/gtest.h>

#include <cmath>

#include "skylight/core/error.h"
#include "skylight/io/image.h"
#include "skylight/models/hosek_wilkie.h"
#include "skylight/nn/image_dataset.h"
#include "support/error_message.h"
#include "support/sky_sequence.h"

namespace skylight::estimate {
namespace {

using testing_support::SequenceDefects;

// Equirect 128 x 64: 2.8 deg per pixel. The centroid of a clipped disc of radius 3 deg lies within
// a pixel of the true sun (the disc's pixels are symmetric about it up to one pixel).
constexpr double kSunFoundTolerance = 2.9 * kDegree;

Camera equirect(int w, int h) {
  return {Projection::equirect, w, h, {}};
}

io::ImageF hosek_capture(const SunPosition& sun, const Camera& cam, const SequenceDefects& x) {
  const HosekWilkieModel model(HosekParameters{sun, 3.0, 0.3});
  return testing_support::render_capture(model, sun, cam, x);
}

TEST(SkySequence, ListColumnsInAnyOrderRelativePathsAndComments) {
  const auto rows = parse_sequence_list(
      "# capture log\nsun_azimuth_deg,file,sun_zenith_deg,mask\n"
      "120,a.exr,40,m.png\n\n200, b.hdr ,60.5,\n",
      "list.csv", "/data/seq");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].file, std::filesystem::path("/data/seq/a.exr"));
  EXPECT_EQ(rows[0].mask, std::filesystem::path("/data/seq/m.png"));
  EXPECT_EQ(*rows[0].sun_zenith_deg, 40.0);
  EXPECT_EQ(*rows[0].sun_azimuth_deg, 120.0);
  EXPECT_EQ(rows[0].line, 3);
  EXPECT_EQ(rows[1].file, std::filesystem::path("/data/seq/b.hdr"));
  EXPECT_EQ(*rows[1].sun_zenith_deg, 60.5);
  EXPECT_TRUE(rows[1].mask.empty());
  EXPECT_EQ(rows[1].line, 5);
  const auto timed =
      parse_sequence_list("file,time\nx.exr,2024-06-21T12:00:00+02:00\ny.exr,\n", "t.csv", "");
  EXPECT_EQ(timed[0].time, "2024-06-21T12:00:00+02:00");
  EXPECT_FALSE(timed[1].sun_zenith_deg.has_value());
  EXPECT_TRUE(timed[1].time.empty());
}

TEST(SkySequence, ListErrorsNameTheFileAndLine) {
  auto message = [](std::string_view text) {
    return testing_support::error_message([&] { parse_sequence_list(text, "seq.csv", ""); });
  };
  EXPECT_EQ(message("file,zenith\n"),
            "seq.csv:1: unknown column 'zenith' (file, sun_zenith_deg, "
            "sun_azimuth_deg, time, mask)");
  EXPECT_EQ(message("file,sun_zenith_deg,sun_azimuth_deg\na.exr,40,10\nb.exr,95,10\n"),
            "seq.csv:3: sun_zenith_deg '95' is outside [0, 90]");
  EXPECT_EQ(message("file,sun_zenith_deg,sun_azimuth_deg\na.exr,1e-999,10\n"),
            "seq.csv:2: sun_zenith_deg '1e-999' underflows to 0 (the smallest non-zero number is "
            "4.94e-324)");
  EXPECT_EQ(message("file,sun_zenith_deg,sun_azimuth_deg\na.exr,40,\n"),
            "seq.csv:2: sun_zenith_deg and sun_azimuth_deg go together");
  EXPECT_EQ(message("file,time\n\na.exr\n"), "seq.csv:3: 1 cells, the header has 2");
  EXPECT_EQ(message("time\n2024-01-01T00:00:00Z\n"), "seq.csv:1: the header has no 'file' column");
  EXPECT_EQ(message("file\n# nothing\n"), "seq.csv: no images listed");
  // Found by the fuzz target sequence_list: a name ending in '/' (or '.', '..') is a folder.
  EXPECT_EQ(message("file\nb.exr../\n"), "seq.csv:2: file 'b.exr../' names a folder, not a file");
  EXPECT_EQ(message("file,mask\na.exr,..\n"), "seq.csv:2: mask '..' names a folder, not a file");
  EXPECT_EQ(message(std::string("file\na\0b.exr\n", 13)),
            "seq.csv:2: file 'a\\x00b.exr' holds a control character");
}

TEST(SkySequence, ClippedSunIsFoundAndExcludedAndTheOccluderMasked) {
  const Camera cam = equirect(128, 64);
  const SunPosition sun{50 * kDegree, 120 * kDegree};
  SequenceDefects x;
  x.sun_radius = 3 * kDegree;
  x.noise = 0.02;
  x.occluder = true;
  const io::ImageF img = hosek_capture(sun, cam, x);
  const io::ImageF mask = testing_support::occluder_mask(cam);
  SequenceSampling s;
  s.samples_per_image = 100000;  // every sky pixel
  const SampledImage r = sample_sky_image(img, cam, std::nullopt, s, &mask);
  EXPECT_TRUE(r.sun_detected);
  const SunPosition found{r.samples.state.sun_zenith, r.samples.state.sun_azimuth};
  EXPECT_LT(angle_between(found.direction(), sun.direction()), kSunFoundTolerance);
  EXPECT_EQ(r.samples.state.turbidity, 0.0);
  EXPECT_EQ(r.samples.views.size(), r.sky_pixels);
  // The upper half minus the sun's exclusion cone and the occluder.
  EXPECT_GT(r.sky_pixels, 128u * 32u * 8u / 10u);
  EXPECT_LT(r.sky_pixels, 128u * 32u);
  float peak = 0.0f;
  for (float v : img.data) peak = std::max(peak, v);
  for (std::size_t i = 0; i < r.samples.views.size(); ++i) {
    const Vec3 v = r.samples.views[i];
    EXPECT_GT(v.z, 0.0);
    EXPECT_GT(angle_between(v, found.direction()), s.mask.sun_exclusion);
    EXPECT_FALSE(testing_support::occluded(v));
    EXPECT_LT(r.samples.rgb[i].g, 0.5 * peak);
  }
  // A given sun is used as given; a sample budget draws that many distinct pixels.
  s.samples_per_image = 500;
  const SampledImage g = sample_sky_image(img, cam, sun, s, &mask);
  EXPECT_FALSE(g.sun_detected);
  EXPECT_EQ(g.samples.state.sun_zenith, sun.zenith);
  EXPECT_EQ(g.samples.views.size(), 500u);
  // A sun below the horizon is refused.
  EXPECT_THROW(sample_sky_image(img, cam, SunPosition{95 * kDegree, 0.0}, s), InvalidArgument);
}

// A network trained on four rendered captures (Hosek-Wilkie T = 3, sun moving from zenith 25 to
// 70 deg and azimuth 100 to 190 deg, clipped sun, 2 % noise, an occluder with its mask) reproduces
// a capture between them that it never saw (zenith 47.5, azimuth 145 deg), against the clean
// render. Four suns under-determine the sun-zenith dependence: a single start sometimes fits them
// more closely and interpolates badly (p95 28-33 % for 2 of 4 sampling seeds), so the best of 3
// starts is trained (TrainOptions::restarts). Measured: relative error median 1.18 %, p95 3.21 %
// (1.0-1.2 % / 3.2-3.9 % over 4 sampling seeds).
constexpr double kHeldOutMedian = 0.03;  // 2.5x the measured median: SIMD-target sums
constexpr double kHeldOutP95 = 0.08;     // 2.5x the measured p95

TEST(SkySequence, FourCaptureNetworkReproducesAHeldOutCapture) {
  const Camera cam = equirect(96, 48);
  const io::ImageF mask = testing_support::occluder_mask(cam);
  SequenceDefects x;
  x.sun_radius = 4 * kDegree;
  x.noise = 0.02;
  x.occluder = true;
  SequenceSampling s;
  s.samples_per_image = 600;
  std::vector<nn::ImageSamples> train;
  for (int k = 0; k < 4; ++k) {
    const SunPosition sun{(25.0 + 15.0 * k) * kDegree, (100.0 + 30.0 * k) * kDegree};
    x.seed = static_cast<std::uint32_t>(k + 1);
    s.seed = static_cast<std::uint64_t>(k + 1);
    train.push_back(
        sample_sky_image(hosek_capture(sun, cam, x), cam, std::nullopt, s, &mask).samples);
  }
  const double scale = nn::image_target_scale(train);
  const nn::Dataset ds = nn::image_dataset(train, nn::satilmis_inputs(), scale);
  nn::NetworkSetup setup;
  setup.options.max_iterations = 150;
  setup.options.restarts = 3;
  const nn::TrainedSkyNetwork net = nn::train_sky_network(ds, setup);
  EXPECT_EQ(net.network.provenance.source, "images");
  EXPECT_EQ(net.network.target_scale, scale);

  const SunPosition held{47.5 * kDegree, 145.0 * kDegree};
  SequenceDefects clean;
  SequenceSampling all;
  all.samples_per_image = 100000;
  const SampledImage h = sample_sky_image(hosek_capture(held, cam, clean), cam, held, all, &mask);
  const nn::Dataset test = nn::image_dataset({h.samples}, nn::satilmis_inputs(), scale);
  const nn::ErrorStats e = nn::evaluate_errors(net.network, test);
  EXPECT_LT(e.relative_median, kHeldOutMedian);
  EXPECT_LT(e.relative_p95, kHeldOutP95);
}

// A real photograph (data/hdr_sky/city.exr, CC0, equirect, clipped sun, buildings): read through
// io, its sun found, the automatic mask applied and sky pixels sampled.
TEST(SkySequence, RealPanoramaIsReadMaskedAndSampled) {
  const io::ImageF img = io::read_image(SKYLIGHT_TEST_DATA_DIR "/hdr_sky/city.exr");
  const Camera cam = equirect(img.width, img.height);
  SequenceSampling s;
  s.samples_per_image = 2000;
  const SampledImage r = sample_sky_image(img, cam, std::nullopt, s);
  EXPECT_TRUE(r.sun_detected);
  // docs/ESTIMATE.md: the sun of city.exr at zenith 42.4 deg, azimuth 216.0 deg.
  EXPECT_NEAR(r.samples.state.sun_zenith / kDegree, 42.4, 0.05);
  EXPECT_NEAR(r.samples.state.sun_azimuth / kDegree, 216.0, 0.05);
  ASSERT_EQ(r.samples.views.size(), 2000u);
  const Vec3 sun = direction_from_angles(r.samples.state.sun_zenith, r.samples.state.sun_azimuth);
  for (std::size_t i = 0; i < r.samples.views.size(); ++i) {
    EXPECT_GE(r.samples.views[i].z, 0.0);
    EXPECT_GT(angle_between(r.samples.views[i], sun), s.mask.sun_exclusion);
    EXPECT_GT(r.samples.rgb[i].r + r.samples.rgb[i].g + r.samples.rgb[i].b, 0.0);
  }
  // The image's unit -> target scale: finite and positive, the median at kImageTargetMedian.
  const double scale = nn::image_target_scale({r.samples});
  EXPECT_GT(scale, 0.0);
  EXPECT_TRUE(std::isfinite(scale));
}

}  // namespace
}  // namespace skylight::estimate
