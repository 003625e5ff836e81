#include "skylight/gpu/context.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "support/gpu_context.h"

namespace skylight::gpu {
namespace {

using testing_support::GpuTest;

TEST_F(GpuTest, ContextIsGl33CoreOrNewer) {
  int major = 0, minor = 0;
  ASSERT_EQ(std::sscanf(context().version().c_str(), "%d.%d", &major, &minor), 2)
      << context().version();
  EXPECT_GE(major * 10 + minor, 33) << context().version();
  EXPECT_FALSE(context().renderer().empty());
}

TEST_F(GpuTest, ConstantShaderReadsBackExactly) {
  // GLSL float literals are IEEE single precision: the target stores them as written.
  FullscreenPass pass;
  pass.fragment_source = std::string(kGlslVersion) +
                         "out vec4 colour;\n"
                         "void main() { colour = vec4(0.1, -2.5e-20, 1.0e30, 0.333333343); }\n";
  const io::ImageF img = run_fullscreen(pass, 7, 5);
  ASSERT_EQ(img.width, 7);
  ASSERT_EQ(img.height, 5);
  ASSERT_EQ(img.channels, 4);
  for (int r = 0; r < img.height; ++r) {
    for (int c = 0; c < img.width; ++c) {
      const float* p = img.pixel(c, r);
      EXPECT_EQ(p[0], 0.1f);
      EXPECT_EQ(p[1], -2.5e-20f);
      EXPECT_EQ(p[2], 1.0e30f);
      EXPECT_EQ(p[3], 0.333333343f);
    }
  }
}

TEST_F(GpuTest, FloatRampSurvivesUnquantisedAndRowsAreNotFlipped) {
  // An input texture whose values an 8- or 16-bit target would round (steps of 2^-20 around 1,
  // negatives, values far above 1) goes through texelFetch at gl_FragCoord and back bit for bit;
  // image row 0 stays row 0.
  const int w = 33, h = 9;
  io::ImageF ramp(w, h, 3);
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c < w; ++c) {
      float* p = ramp.pixel(c, r);
      p[0] = 1.0f + static_cast<float>(c + w * r) * 0x1p-20f;
      p[1] = -1.0e-3f * static_cast<float>(c) + 7.0e4f * static_cast<float>(r);
      p[2] = static_cast<float>(r);
    }
  }
  FullscreenPass pass;
  pass.fragment_source =
      std::string(kGlslVersion) +
      "uniform sampler2D ramp;\n"
      "uniform float scale;\n"
      "out vec4 colour;\n"
      "void main() {\n"
      "  colour = vec4(texelFetch(ramp, ivec2(gl_FragCoord.xy), 0).rgb * scale,\n"
      "                gl_FragCoord.y);\n"
      "}\n";
  pass.uniforms.emplace_back("scale", 1.0f);
  pass.inputs.emplace_back("ramp", &ramp);
  const io::ImageF out = run_fullscreen(pass, w, h);
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c < w; ++c) {
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(out.pixel(c, r)[k], ramp.pixel(c, r)[k]) << c << "," << r;
      // gl_FragCoord.y counts pixel centres from the bottom.
      EXPECT_EQ(out.pixel(c, r)[3], static_cast<float>(h - r) - 0.5f);
    }
  }
}

TEST_F(GpuTest, CompileErrorIsAGpuErrorWithTheInfoLog) {
  try {
    Program::fullscreen(std::string(kGlslVersion) +
                        "out vec4 colour;\nvoid main() { colour = undeclared_thing; }\n");
    FAIL() << "a shader with an undeclared identifier compiled";
  } catch (const GpuError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("fragment shader does not compile"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("undeclared_thing"));
  }
}

TEST_F(GpuTest, UnknownUniformIsAnError) {
  Program p = Program::fullscreen(std::string(kGlslVersion) +
                                  "uniform float k;\nout vec4 colour;\n"
                                  "void main() { colour = vec4(k); }\n");
  p.set("k", 1.0f);
  EXPECT_THROW(p.set("no_such_uniform", 1.0f), GpuError);
}

TEST_F(GpuTest, MeshPathDrawsAttributesWithTheDepthTest) {
  // A far triangle covering the whole target (value 1) and a near one covering the lower-left
  // half (value 2, drawn first: the depth test keeps it).
  const char* vs =
      "#version 330 core\n"
      "in vec3 position;\nin vec3 attribute1;\nout vec3 value;\n"
      "void main() { value = attribute1; gl_Position = vec4(position, 1.0); }\n";
  const char* fs =
      "#version 330 core\n"
      "in vec3 value;\nout vec4 colour;\nvoid main() { colour = vec4(value, 1.0); }\n";
  Program p(vs, fs);
  Target t(16, 16);
  t.clear();
  const float near_pos[] = {-1, -1, -0.5f, 1, -1, -0.5f, -1, 1, -0.5f};
  const float near_val[] = {2, 2, 2, 2, 2, 2, 2, 2, 2};
  const float far_pos[] = {-1, -1, 0.5f, 3, -1, 0.5f, -1, 3, 0.5f};
  const float far_val[] = {1, 1, 1, 1, 1, 1, 1, 1, 1};
  const unsigned tri[] = {0, 1, 2};
  t.draw_mesh(p, near_pos, near_val, tri);
  t.draw_mesh(p, far_pos, far_val, tri);
  const io::ImageF img = t.read(1);
  // Pixel (c, r), r from the top: lower-left half in GL coordinates is x + y < 1 in NDC.
  for (int r = 0; r < 16; ++r) {
    for (int c = 0; c < 16; ++c) {
      const double x = (c + 0.5) / 8.0 - 1.0, y = 1.0 - (r + 0.5) / 8.0;
      if (std::abs(x + y) < 0.1) continue;  // the shared edge
      EXPECT_EQ(img.pixel(c, r)[0], x + y < 0.0 ? 2.0f : 1.0f) << c << "," << r;
    }
  }
}

TEST_F(GpuTest, MeshIndexBeyondTheVerticesIsAnError) {
  Program p(std::string(kGlslVersion) +
                "in vec3 position;\nvoid main() { gl_Position = vec4(position, 1.0); }\n",
            std::string(kGlslVersion) + "out vec4 c;\nvoid main() { c = vec4(1.0); }\n");
  Target t(4, 4);
  const float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const unsigned bad[] = {0, 1, 3};
  EXPECT_THROW(t.draw_mesh(p, pos, {}, bad), GpuError);
}

}  // namespace
}  // namespace skylight::gpu
