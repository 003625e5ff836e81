#include "skylight/nn/dataset.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "skylight/core/error.h"
#include "support/analytic_sky.h"

namespace skylight::nn {
namespace {

// Double-precision geometry (rotations, chord lengths) agrees to round-off.
constexpr double kGeometryTolerance = 1e-12;

// The paper's turbidities: Preetham 2..6 (validation 2.5..5.5), Hosek 1..10 (1.5..9.5).
std::vector<double> steps(double first, double last) {
  std::vector<double> t;
  for (double v = first; v <= last + 1e-9; v += 1.0) t.push_back(v);
  return t;
}

SamplingSpec small_spec(const char* model) {
  SamplingSpec s = paper_training_spec(model, {3.0}, 683.0);
  s.turbidities = {3.0};
  s.sun_count = 2;
  s.view_zeniths = 3;
  s.view_azimuths = 4;
  return s;
}

TEST(Dataset, PaperProtocolSizes) {
  auto count = [](const SamplingSpec& s) {
    return s.turbidities.size() * s.sun_count * s.view_zeniths * s.view_azimuths;
  };
  EXPECT_EQ(count(paper_training_spec("preetham", steps(2, 6), 1000.0)), 20000u);  // Table 1
  EXPECT_EQ(count(paper_training_spec("hosek", steps(1, 10), 683.0)), 40000u);     // Table 1
  EXPECT_EQ(count(paper_validation_spec("preetham", steps(2.5, 5.5), 1000.0)), 4u * 7 * 200);
  EXPECT_EQ(count(paper_validation_spec("hosek", steps(1.5, 9.5), 683.0)), 9u * 7 * 200);
  EXPECT_DOUBLE_EQ(paper_validation_spec("hosek", steps(1.5, 9.5), 683.0).turbidities.front(), 1.5);
  EXPECT_DOUBLE_EQ(paper_validation_spec("hosek", steps(1.5, 9.5), 683.0).turbidities.back(), 9.5);
  EXPECT_DOUBLE_EQ(paper_training_spec("hosek", steps(1, 10), 683.0).ground_albedo, 0.5);
}

TEST(Dataset, RotationMovesTheSunToAzimuthPi) {
  for (double phi : {0.0, 0.4, 2.0, kPi, 4.5, 6.1}) {
    const Vec3 sun = direction_from_angles(0.7, phi);
    const Vec3 r = rotate_view_to_reference(sun, phi);
    const Vec3 ref = direction_from_angles(0.7, kPi);
    EXPECT_NEAR(r.x, ref.x, kGeometryTolerance);
    EXPECT_NEAR(r.y, ref.y, kGeometryTolerance);
    EXPECT_NEAR(r.z, ref.z, kGeometryTolerance);
  }
}

TEST(Dataset, SatilmisInputs) {
  SkyState s;
  s.turbidity = 4.0;
  s.sun_zenith = 0.6;
  s.sun_azimuth = 1.0;
  const Vec3 view = direction_from_angles(1.1, 2.5);
  std::vector<double> in(6);
  compute_inputs(satilmis_inputs(), s, view, in);
  EXPECT_DOUBLE_EQ(in[0], 2.0);                                  // sqrt t
  EXPECT_DOUBLE_EQ(in[1], 0.6);                                  // theta_sun
  const Vec3 v = direction_from_angles(1.1, 2.5 - (1.0 - kPi));  // eq. 10 in azimuth form
  EXPECT_NEAR(in[2], v.x, kGeometryTolerance);
  EXPECT_NEAR(in[3], v.y, kGeometryTolerance);
  EXPECT_NEAR(in[4], v.z, kGeometryTolerance);
  const double gamma = angle_between(view, direction_from_angles(0.6, 1.0));
  EXPECT_NEAR(in[5], 2.0 * std::sin(gamma / 2.0), kGeometryTolerance);  // d = 2 sin(gamma/2)
}

TEST(Dataset, InputSpecParsing) {
  EXPECT_EQ(parse_inputs(to_string(satilmis_inputs())), satilmis_inputs());
  EXPECT_THROW(parse_inputs("sqrt_turbidity,bogus"), InvalidArgument);
  EXPECT_TRUE(is_state_input(Input::sun_zenith));
  EXPECT_FALSE(is_state_input(Input::chord));
}

TEST(Dataset, EncodingsRoundTrip) {
  for (double L : {0.05, 1.0, 37.0}) {
    for (auto e : {OutputEncoding::satilmis, OutputEncoding::log, OutputEncoding::root4,
                   OutputEncoding::root8}) {
      EXPECT_EQ(parse_output_encoding(to_string(e)), e);
      EXPECT_NEAR(decode_radiance(e, encode_radiance(e, L)), L, 1e-12 * L);
    }
  }
  EXPECT_DOUBLE_EQ(encode_radiance(OutputEncoding::satilmis, 0.0), 1.0);   // L_s^-1(0)
  EXPECT_DOUBLE_EQ(encode_radiance(OutputEncoding::satilmis, 1.5), 0.25);  // 1 / (1 + 3)
  EXPECT_DOUBLE_EQ(encode_radiance(OutputEncoding::satilmis, -0.2), 1.0);  // clamped at 0
  EXPECT_DOUBLE_EQ(decode_radiance(OutputEncoding::satilmis, 0.25), 1.5);  // eq. 7
}

TEST(Dataset, StratifiedViewsAndSourceRadiance) {
  const SamplingSpec spec = small_spec("hosek");
  const Dataset ds =
      build_dataset(spec, satilmis_inputs(), testing_support::analytic_sky_source(683.0));
  ASSERT_EQ(ds.size(), 2u * 12);
  std::set<std::pair<int, int>> strata;
  for (std::size_t i = 0; i < 12; ++i) {  // the first state's views: one per stratum
    const auto za = angles_from_direction(ds.views[i]);
    EXPECT_GE(ds.views[i].z, 0.0);
    strata.insert({static_cast<int>(za.zenith / (kPi / 2) * 3),
                   static_cast<int>(za.azimuth / (2 * kPi) * 4)});
  }
  EXPECT_EQ(strata.size(), 12u);
  EXPECT_DOUBLE_EQ(ds.states[0].sun_zenith, 0.25 * kPi / 2);  // midpoints of 2 strata
  EXPECT_DOUBLE_EQ(ds.states[1].sun_zenith, 0.75 * kPi / 2);
  const Rgb c = testing_support::analytic_sky(ds.states[1], ds.views[20], 683.0);
  EXPECT_DOUBLE_EQ(ds.radiance[3 * 20 + 1], c.g / 683.0);
  // Same seed, same set.
  const Dataset again =
      build_dataset(spec, satilmis_inputs(), testing_support::analytic_sky_source(683.0));
  EXPECT_EQ(again.inputs, ds.inputs);
}

TEST(Dataset, ValidationSunsHaveVariedAzimuths) {
  SamplingSpec spec = paper_validation_spec("preetham", steps(2.5, 5.5), 1000.0);
  spec.view_zeniths = 1;
  spec.view_azimuths = 1;
  const Dataset ds =
      build_dataset(spec, satilmis_inputs(), testing_support::analytic_sky_source(683.0));
  std::set<double> az;
  for (const auto& s : ds.states) az.insert(s.sun_azimuth);
  EXPECT_EQ(az.size(), ds.states.size());
}

}  // namespace
}  // namespace skylight::nn
