#include "skylight/gpu/network.h"

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <string>

#include "skylight/core/error.h"
#include "skylight/gpu/context.h"
#include "skylight/nn/glsl.h"

namespace skylight::gpu {

namespace {
// Examples per target row: one pixel each.
constexpr std::size_t kRowWidth = 1024;
constexpr const char* kChannels = "rgba";
}  // namespace

std::vector<float> evaluate_mlp(const nn::Mlp& net, std::span<const float> inputs) {
  const nn::MlpLayout& l = net.layout();
  l.validate();
  const auto n_in = static_cast<std::size_t>(l.inputs());
  const auto n_out = static_cast<std::size_t>(l.outputs());
  if (inputs.size() % n_in != 0)
    throw InvalidArgument(
        fmt::format("evaluate_mlp: {} input values are not a multiple of {}", inputs.size(), n_in));
  const std::size_t n = inputs.size() / n_in;
  std::vector<float> out(n * n_out);
  if (n == 0) return out;
  const int width = static_cast<int>(std::min(n, kRowWidth));
  const int height = static_cast<int>((n + kRowWidth - 1) / kRowWidth);
  // Inputs 4 per RGBA texture, example i at pixel (i % width, i / width).
  const std::size_t textures = (n_in + 3) / 4;
  std::vector<io::ImageF> images(textures, io::ImageF(width, height, 4));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < n_in; ++k) images[k / 4].data[4 * i + k % 4] = inputs[i * n_in + k];
  std::vector<std::unique_ptr<Texture>> tex;
  for (const auto& img : images) tex.push_back(std::make_unique<Texture>(img));
  const std::string network = nn::glsl_mlp(net, "skylight_network");
  Target target(width, height);
  // Four outputs per pass.
  for (std::size_t group = 0; group < (n_out + 3) / 4; ++group) {
    std::string src(kGlslVersion);
    src += network;
    for (std::size_t t = 0; t < textures; ++t) src += fmt::format("uniform sampler2D in{};\n", t);
    src += "out vec4 colour;\nvoid main() {\n  ivec2 p = ivec2(gl_FragCoord.xy);\n";
    for (std::size_t t = 0; t < textures; ++t)
      src += fmt::format("  vec4 t{0} = texelFetch(in{0}, p, 0);\n", t);
    src += fmt::format("  float x[{}];\n", n_in);
    for (std::size_t k = 0; k < n_in; ++k)
      src += fmt::format("  x[{}] = t{}.{};\n", k, k / 4, kChannels[k % 4]);
    src += fmt::format("  float y[{}];\n  skylight_network(x, y);\n", n_out);
    std::string c[4];
    for (std::size_t k = 0; k < 4; ++k) {
      const std::size_t o = 4 * group + k;
      c[k] = o < n_out ? fmt::format("y[{}]", o) : "0.0";
    }
    src += fmt::format("  colour = vec4({}, {}, {}, {});\n}}\n", c[0], c[1], c[2], c[3]);
    Program program = Program::fullscreen(src);
    for (std::size_t t = 0; t < textures; ++t)
      program.bind(fmt::format("in{}", t), *tex[t], static_cast<int>(t));
    target.clear();
    target.draw_fullscreen(program);
    const io::ImageF result = target.read(4);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < 4 && 4 * group + k < n_out; ++k)
        out[i * n_out + 4 * group + k] = result.data[4 * i + k];
  }
  return out;
}

}  // namespace skylight::gpu
