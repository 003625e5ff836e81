#include "skylight/nn/glsl.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <random>

#include "skylight/core/error.h"
#include "support/glslang.h"
#include "support/scratch_dir.h"

namespace skylight::nn {
namespace {

using testing_support::run_glslang;
using testing_support::ScratchDir;

// Random weights in [-1, 1] (the exported code does not depend on their values).
Mlp random_mlp(const MlpLayout& layout, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> p(layout.parameter_count());
  for (double& v : p) v = u(rng);
  return Mlp(layout, p);
}

SkyNetwork random_sky(InputSpec inputs, OutputEncoding encoding, Activation hidden,
                      Activation output, unsigned seed) {
  SkyNetwork sky;
  sky.inputs = inputs;
  sky.encoding = encoding;
  sky.target_scale = 683.0;
  sky.net = random_mlp(MlpLayout::make(static_cast<int>(inputs.size()), {12, 5}, 3, hidden, output),
                       seed);
  sky.provenance.source = "preetham\nwith a newline";
  return sky;
}

// A fragment shader main() that calls the exported entry points, linked with the file.
constexpr const char* kCaller =
    "#version 330 core\n"
    "vec3 skylight_sky(vec3 view, vec3 sun, float turbidity);\n"
    "vec3 skylight_sky_state(vec3 view, float sun_zenith, float sun_azimuth, float turbidity);\n"
    "in vec3 view;\nout vec4 colour;\n"
    "void main() {\n"
    "  colour = vec4(skylight_sky(view, vec3(0.0, -0.6, 0.8), 3.0) +\n"
    "                skylight_sky_state(view, 0.6, 3.1, 3.0), 1.0);\n"
    "}\n";

void expect_valid(const SkyNetwork& sky, const ScratchDir& dir, const std::string& name) {
  const auto file = dir / (name + ".glsl");
  const auto caller = dir / "caller.frag";
  std::ofstream(file) << glsl_sky_network_file(sky);
  std::ofstream(caller) << kCaller;
  for (const char* stage : {"frag", "vert"}) {
    const auto r =
        run_glslang(std::string("-S ") + stage + " '" + file.string() + "'", dir / "log.txt");
    EXPECT_EQ(r.status, 0) << name << " (" << stage << "):\n" << r.output;
  }
  const auto linked =
      run_glslang("-l -S frag '" + file.string() + "' '" + caller.string() + "'", dir / "log.txt");
  EXPECT_EQ(linked.status, 0) << name << " linked with a caller:\n" << linked.output;
}

TEST(Glsl, SatilmisSkyNetworkFileIsValidGlsl) {
  ScratchDir dir;
  expect_valid(random_sky(satilmis_inputs(), OutputEncoding::satilmis, Activation::satilmis,
                          Activation::satilmis, 1),
               dir, "satilmis");
}

// A network with a radiance bound clamps the decoded radiance in GLSL as on the CPU.
TEST(Glsl, MaxRadianceIsClampedInGlsl) {
  ScratchDir dir;
  SkyNetwork sky = random_sky(satilmis_inputs(), OutputEncoding::satilmis, Activation::satilmis,
                              Activation::satilmis, 1);
  EXPECT_EQ(glsl_sky_network(sky).find("min(vec3("), std::string::npos);
  sky.max_radiance = 0.25;
  EXPECT_NE(glsl_sky_network(sky).find("min(vec3("), std::string::npos);
  expect_valid(sky, dir, "bounded");
}

TEST(Glsl, EveryActivationInputAndEncodingIsValidGlsl) {
  ScratchDir dir;
  const InputSpec all = {Input::sqrt_turbidity,
                         Input::sun_zenith,
                         Input::view_x,
                         Input::view_y,
                         Input::view_z,
                         Input::chord,
                         Input::log_chord,
                         Input::sqrt_view_z,
                         Input::aureole,
                         Input::cos_sun_zenith,
                         Input::sun_elevation_cbrt,
                         Input::turbidity};
  const Activation acts[] = {Activation::identity, Activation::satilmis, Activation::pietras,
                             Activation::tanh,     Activation::sigmoid,  Activation::relu,
                             Activation::softplus};
  const OutputEncoding encodings[] = {OutputEncoding::satilmis, OutputEncoding::log,
                                      OutputEncoding::root4, OutputEncoding::root8};
  unsigned seed = 2;
  for (Activation a : acts) {
    for (OutputEncoding e : encodings) {
      expect_valid(random_sky(all, e, a, Activation::identity, seed++), dir,
                   std::string(to_string(a)) + "_" + std::string(to_string(e)));
    }
  }
}

TEST(Glsl, PietrasNetworksAreValidVertexShaderGlsl) {
  // Both kinds, with a vertex shader main() calling skylight_pietras (gpu/planet.h's use).
  ScratchDir dir;
  for (const auto kind : {PietrasKind::pietras, PietrasKind::log3}) {
    const PietrasNetwork net = initial_pietras_network(kind, 3);
    const std::string name(to_string(kind));
    const auto file = dir / (name + ".vert");
    std::ofstream(file) << "#version 330 core\n"
                        << glsl_pietras_network(net)
                        << "in vec4 x;\nout vec3 c;\nvoid main() {\n  c = skylight_pietras(x);\n"
                           "  gl_Position = vec4(0.0);\n}\n";
    const auto r = run_glslang("-S vert '" + file.string() + "'", dir / "log.txt");
    EXPECT_EQ(r.status, 0) << name << ":\n" << r.output;
  }
  PietrasNetwork bad = initial_pietras_network(PietrasKind::pietras, 3);
  bad.subnets.pop_back();
  EXPECT_THROW(glsl_pietras_network(bad), InvalidArgument);
}

TEST(Glsl, WeightsAreBakedInAsRoundTripFloats) {
  // Every parameter appears as a literal that parses back to the same float.
  const Mlp net = random_mlp(MlpLayout::make(2, {3}, 1, Activation::tanh, Activation::identity), 7);
  const std::string s = glsl_mlp(net, "f");
  for (double p : net.parameters()) {
    const std::string lit = fmt::format("{:.8e}", static_cast<float>(p));
    EXPECT_NE(s.find(lit), std::string::npos) << lit;
    EXPECT_EQ(std::stof(lit), static_cast<float>(p));
  }
  EXPECT_THAT(s, ::testing::HasSubstr("void f(in float x[2], out float y[1])"));
  EXPECT_THAT(s, ::testing::HasSubstr("float skylight_act_tanh(float x)"));
}

TEST(Glsl, BadFunctionNameIsRejected) {
  const Mlp net(MlpLayout::make(2, {3}, 1, Activation::tanh, Activation::identity));
  EXPECT_THROW(glsl_mlp(net, "1bad"), InvalidArgument);
  EXPECT_THROW(glsl_mlp(net, "a b"), InvalidArgument);
}

TEST(Glsl, ProvenanceTextCannotBreakTheComment) {
  const std::string s = glsl_sky_network_file(random_sky(
      satilmis_inputs(), OutputEncoding::satilmis, Activation::satilmis, Activation::satilmis, 3));
  EXPECT_THAT(s, ::testing::HasSubstr("// Trained on: preetham with a newline"));
}

}  // namespace
}  // namespace skylight::nn
