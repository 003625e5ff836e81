// A headless OpenGL harness (docs/GPU.md): an EGL surfaceless context (Mesa llvmpipe on machines
// without a GPU), OpenGL 3.3 core profile, shader programs, float textures in and a float render
// target out, read back as io::ImageF.
//
// Orientation: io::ImageF row 0 is the top of the image; GL's window row 0 is the bottom. Every
// texture is uploaded and every target read back flipped, so the fragment at gl_FragCoord.xy
// (pixel centres at +0.5, y up) is image pixel (col, row) = (x, height - y) - 0.5, and
// texelFetch(tex, ivec2(gl_FragCoord.xy), 0) reads the same pixel of an input image of the
// output's size.
//
// Only gpu/ (and the CLI, through it) includes GL or EGL headers; this header includes neither.
#pragma once

#include <array>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "skylight/io/image.h"

namespace skylight::gpu {

// No GL at run time (no EGL display, no surfaceless platform, no GL 3.3 context), a shader that
// does not compile or link (the message holds the GL info log), or a GL error. The CLI reports it
// on one line (exit status 1).
class GpuError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The GLSL version line every shader of the harness starts with (GL 3.3 core).
inline constexpr std::string_view kGlslVersion = "#version 330 core\n";

// A GL 3.3 core context on the process-wide EGL surfaceless display (initialised on first use,
// never terminated: docs/GPU.md), current on the calling thread while it lives. One
// Context per thread at a time; GL objects (Program, Texture, Target) must not outlive it.
class Context {
 public:
  // Throws GpuError with one line saying what is missing.
  Context();
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  std::string renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string version() const;   // GL_VERSION
  // Blocks until every command issued so far has completed (glFinish).
  void finish() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A float texture (R32F, RG32F, RGB32F or RGBA32F by channel count), nearest filtering, clamped
// to the edge; rows flipped (see the header comment).
class Texture {
 public:
  explicit Texture(const io::ImageF& image);
  ~Texture();
  Texture(const Texture&) = delete;
  Texture& operator=(const Texture&) = delete;
  unsigned id() const { return id_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  unsigned id_ = 0;
  int width_ = 0, height_ = 0;
};

using UniformValue =
    std::variant<int, float, std::array<float, 2>, std::array<float, 3>, std::array<float, 4>>;

// A linked vertex + fragment program. Compile and link errors throw GpuError with the stage and
// the GL info log.
class Program {
 public:
  Program(std::string_view vertex_source, std::string_view fragment_source);
  // A fragment shader over the full-screen quad: the vertex shader is the harness's
  // (kFullscreenVertexShader), which passes nothing but the position.
  static Program fullscreen(std::string_view fragment_source);
  ~Program();
  Program(Program&& other) noexcept;
  Program& operator=(Program&&) = delete;
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  unsigned id() const { return id_; }
  // Sets a uniform by name (the program is made current); a name the linker removed or never
  // had throws GpuError, so a typo cannot pass silently.
  void set(std::string_view name, const UniformValue& value);
  // The same for a uniform the generated code may not use (the compiler removes it): returns
  // false and sets nothing when `name` is not active.
  bool set_if_active(std::string_view name, const UniformValue& value);
  // Binds `texture` to the sampler uniform `name` on texture unit `unit`.
  void bind(std::string_view name, const Texture& texture, int unit);

 private:
  explicit Program(unsigned id) : id_(id) {}
  unsigned id_ = 0;
  std::vector<std::pair<int, unsigned>> textures_;  // (unit, texture id)
  friend class Target;
};

// The vertex shader of Program::fullscreen: two triangles covering clip space.
extern const std::string_view kFullscreenVertexShader;

// An RGBA32F colour buffer + 24-bit depth buffer of width x height.
class Target {
 public:
  Target(int width, int height);
  ~Target();
  Target(const Target&) = delete;
  Target& operator=(const Target&) = delete;
  int width() const { return width_; }
  int height() const { return height_; }

  // Clears colour to `clear` and depth to 1.
  void clear(std::array<float, 4> clear = {0, 0, 0, 0});
  // Runs `program`'s fragment shader once per pixel (full-screen quad, no depth test).
  void draw_fullscreen(const Program& program);
  // Draws indexed triangles: vertex attribute 0 = vec3 positions (3 floats per vertex), optional
  // attribute 1 = vec3 per vertex (e.g. normals; empty: none), with the depth test (less).
  void draw_mesh(const Program& program, std::span<const float> positions,
                 std::span<const float> attribute1, std::span<const unsigned> indices);
  // The same with any vertex attributes: attribute i (layout(location = i) in the shader) takes
  // `components` (1..4) floats per vertex from `values`; every attribute has the same vertex count.
  struct Attribute {
    int components = 3;
    std::span<const float> values;
  };
  void draw_mesh(const Program& program, std::span<const Attribute> attributes,
                 std::span<const unsigned> indices);
  // The colour buffer, the first `channels` (1..4) of RGBA, row 0 at the top.
  io::ImageF read(int channels = 4) const;

 private:
  unsigned fbo_ = 0, colour_ = 0, depth_ = 0;
  int width_ = 0, height_ = 0;
};

// Convenience: one full-screen pass of `fragment_source` with uniforms and input images (sampler
// name -> image, units in order) into a new width x height target, read back with `channels`.
struct FullscreenPass {
  std::string fragment_source;
  std::vector<std::pair<std::string, UniformValue>> uniforms;
  std::vector<std::pair<std::string, const io::ImageF*>> inputs;
};
io::ImageF run_fullscreen(const FullscreenPass& pass, int width, int height, int channels = 4);

}  // namespace skylight::gpu
