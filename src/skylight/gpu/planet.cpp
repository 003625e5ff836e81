#include "skylight/gpu/planet.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "skylight/core/error.h"
#include "skylight/core/icosphere.h"
#include "skylight/core/math.h"
#include "skylight/core/parallel.h"
#include "skylight/gpu/context.h"
#include "skylight/nn/glsl.h"

namespace skylight::gpu {

namespace {

// The shell's depth in normalised device coordinates: just in front of the far end (1), behind
// every ground point closer than ~1000 km from the ground view's near plane of 1 m
// (z_ndc = 1 - 2 near / z), so the ground covers the shell wherever both are drawn.
constexpr double kShellDepthNdc = 1.0 - 2e-6;
// Near plane inside the atmosphere [m] (the ground mesh lies below the sphere, so nothing
// visible is closer).
constexpr double kNearInsideM = 1.0;
// Unit-vector checks of a view's frame.
constexpr double kUnitTolerance = 1e-9;
// Orbit view: the atmosphere's disc fills this fraction of the vertical field of view.
constexpr double kOrbitFill = 0.85;
// Width of the per-vertex comparison target [px].
constexpr std::size_t kVertexRowWidth = 1024;

void check_view(const PlanetView& v, double r0) {
  auto unit = [](Vec3 a) { return std::abs(length(a) - 1.0) <= kUnitTolerance; };
  if (!unit(v.forward) || !unit(v.up) || !unit(v.sun) ||
      std::abs(dot(v.forward, v.up)) > kUnitTolerance)
    throw InvalidArgument(
        "planet view: forward, up and sun must be unit vectors, forward orthogonal to up");
  if (!(length(v.camera_m) > r0))
    throw InvalidArgument(
        fmt::format("planet view: the camera ({:.0f} m from the centre) is not above the ground "
                    "(radius {:.0f} m)",
                    length(v.camera_m), r0));
  if (!(v.vertical_fov > 0.0 && v.vertical_fov < kPi))
    throw InvalidArgument("planet view: the field of view must be in (0, 180) degrees");
  if (!(v.albedo >= 0.0 && v.albedo <= 1.0))
    throw InvalidArgument(fmt::format("planet view: albedo {} is not in [0, 1]", v.albedo));
  if (v.width < 1 || v.height < 1)
    throw InvalidArgument(fmt::format("planet view: size {}x{}", v.width, v.height));
}

// An orthonormal frame with `z` as its third axis: world -> local coordinates.
struct LocalFrame {
  Vec3 x, y, z;
  explicit LocalFrame(Vec3 zenith) : z(zenith) {
    const Vec3 a = std::abs(z.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
    x = normalize(cross(a, z));
    y = cross(z, x);
  }
  Vec3 operator()(Vec3 v) const { return {dot(v, x), dot(v, y), dot(v, z)}; }
};

std::array<float, 4> to_float4(const nn::PietrasInput& in) {
  return {static_cast<float>(in.cos_view_zenith), static_cast<float>(in.cos_view_sun),
          static_cast<float>(in.cos_sun_zenith), static_cast<float>(in.density)};
}

// The vertex attributes of the shader, float, in its locations' order.
struct Attributes {
  std::vector<float> clip, observer, probe, weights, transmittance, reflected;
  void add(const std::array<double, 4>& c, const PlanetVertex& v) {
    for (double x : c) clip.push_back(static_cast<float>(x));
    for (float x : to_float4(v.observer)) observer.push_back(x);
    for (float x : to_float4(v.probe)) probe.push_back(x);
    weights.push_back(static_cast<float>(v.observer_weight));
    weights.push_back(static_cast<float>(v.probe_weight));
    for (double x : v.transmittance) transmittance.push_back(static_cast<float>(x));
    for (double x : {v.reflected.r, v.reflected.g, v.reflected.b})
      reflected.push_back(static_cast<float>(x));
  }
  std::vector<Target::Attribute> spans() const {
    return {{4, clip}, {4, observer}, {4, probe}, {2, weights}, {3, transmittance}, {3, reflected}};
  }
};

io::ImageF draw(const nn::PietrasNetwork& net, const Attributes& a,
                const std::vector<unsigned>& indices, int width, int height, bool flat) {
  Program program(planet_vertex_shader(net, flat), planet_fragment_shader(flat));
  Target target(width, height);
  target.clear();
  const auto spans = a.spans();
  target.draw_mesh(program, spans, indices);
  return target.read(4);
}

}  // namespace

PlanetView orbit_view(const NishitaParameters& planet, double altitude_m, double sun_zenith) {
  PlanetView v;
  const double r = planet.ground_radius_m + altitude_m;
  v.camera_m = {0.0, 0.0, r};
  v.forward = {0.0, 0.0, -1.0};
  v.up = {0.0, 1.0, 0.0};
  const double half = std::asin(std::min(planet.top_radius() / r, 1.0));
  v.vertical_fov = std::min(2.0 * half / kOrbitFill, 170.0 * kDegree);
  v.sun = {std::sin(sun_zenith), 0.0, std::cos(sun_zenith)};
  return v;
}

PlanetView ground_view(const NishitaParameters& planet, double altitude_m, double sun_zenith,
                       double sun_azimuth, double look_elevation) {
  PlanetView v;
  v.camera_m = {0.0, 0.0, planet.ground_radius_m + altitude_m};
  v.forward = {0.0, std::cos(look_elevation), std::sin(look_elevation)};
  v.up = {0.0, -std::sin(look_elevation), std::cos(look_elevation)};
  v.sun = direction_from_angles(sun_zenith, sun_azimuth);
  return v;
}

PlanetMesh planet_mesh(const nn::PietrasNetwork& net, const NishitaSampler& atmosphere,
                       const PlanetView& view) {
  const NishitaParameters& p = atmosphere.parameters();
  const double r0 = p.ground_radius_m, rt = p.top_radius();
  const double top = rt - r0;
  check_view(view, r0);
  const Icosphere sphere = icosphere(view.subdivisions);
  const std::size_t n = sphere.vertices.size();
  PlanetMesh m;
  m.ground_vertices = n;
  m.clip.resize(2 * n);
  m.vertices.resize(2 * n);
  m.indices = sphere.indices;
  for (unsigned i : sphere.indices) m.indices.push_back(i + static_cast<unsigned>(n));

  const Vec3 c = view.camera_m;
  const double rc = length(c);
  const bool outside = rc > rt;
  const Vec3 right = cross(view.forward, view.up);
  const double tan_half = std::tan(0.5 * view.vertical_fov);
  const double aspect = static_cast<double>(view.width) / view.height;
  const double near = outside ? 0.5 * (rc - rt) : kNearInsideM;
  const double far = rc + rt;
  const double depth_a = (far + near) / (far - near), depth_b = -2.0 * far * near / (far - near);

  parallel_for(2 * n, 64, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const bool ground = i < n;
      const Vec3 vtx = (ground ? r0 : rt) * sphere.vertices[i % n];
      const Vec3 d = vtx - c;
      const double z = dot(d, view.forward);
      m.clip[i] = {dot(d, right) / (tan_half * aspect), dot(d, view.up) / tan_half,
                   ground ? depth_a * z + depth_b : kShellDepthNdc * z, z};
      const double dist = length(d);
      const Vec3 dir = (1.0 / dist) * d;
      PlanetVertex& v = m.vertices[i];
      if (ground && dot(dir, sphere.vertices[i % n]) >= 0.0) continue;  // faces away: black
      // E: the observer, or where the view ray enters the top sphere.
      Vec3 eval = c;
      double remaining = dist;
      if (outside) {
        const double bb = dot(c, dir), cc = rc * rc - rt * rt;
        const double t0 = std::clamp(-bb - std::sqrt(std::max(bb * bb - cc, 0.0)), 0.0, dist);
        eval = c + t0 * dir;
        remaining = dist - t0;
      }
      const double re = length(eval);
      const LocalFrame local((1.0 / re) * eval);
      const double h = std::clamp(re - r0, 0.0, top);
      if (!ground) {
        const double ct = dot(view.sun, local.z);
        v.observer = {dot(dir, local.z), dot(dir, view.sun), ct, net.density(h)};
        v.observer_weight = net.lit(h, v.observer.cos_view_zenith, v.observer.cos_view_sun, ct);
        continue;
      }
      const PietrasSurfaceTerms t =
          pietras_surface_terms(atmosphere, h, local(dir), remaining, view.albedo, local(view.sun));
      v.observer = {t.observer_cos_view_zenith, t.cos_view_sun, t.observer_cos_sun_zenith,
                    net.density(t.observer_altitude_m)};
      v.observer_weight = net.lit(t.observer_altitude_m, t.observer_cos_view_zenith, t.cos_view_sun,
                                  t.observer_cos_sun_zenith);
      v.probe = {t.probe_cos_view_zenith, t.cos_view_sun, t.probe_cos_sun_zenith,
                 net.density(t.probe_altitude_m)};
      v.probe_weight = net.lit(t.probe_altitude_m, t.probe_cos_view_zenith, t.cos_view_sun,
                               t.probe_cos_sun_zenith);
      v.transmittance = t.transmittance;
      v.reflected = t.reflected;
    }
  });
  return m;
}

Rgb shade_planet_vertex(const nn::PietrasNetwork& net, const PlanetVertex& v) {
  // The vertex shader's order of operations (planet_vertex_shader).
  Rgb c = v.reflected;
  if (v.observer_weight != 0.0) {
    const Rgb o = net.rgb(v.observer);
    c = {c.r + v.observer_weight * o.r, c.g + v.observer_weight * o.g,
         c.b + v.observer_weight * o.b};
  }
  if (v.probe_weight != 0.0) {
    const Rgb q = net.rgb(v.probe);
    const auto& t = v.transmittance;
    c = {c.r - v.probe_weight * t[0] * q.r, c.g - v.probe_weight * t[1] * q.g,
         c.b - v.probe_weight * t[2] * q.b};
  }
  return {std::max(c.r, 0.0), std::max(c.g, 0.0), std::max(c.b, 0.0)};
}

std::string planet_vertex_shader(const nn::PietrasNetwork& net, bool flat) {
  std::string s(kGlslVersion);
  s += "// skylight: the Pietras vertex shader of a planet and its atmosphere (docs/PIETRAS.md).\n";
  s += nn::glsl_pietras_network(net);
  s += "\nlayout(location = 0) in vec4 skylight_clip;\n"
       "layout(location = 1) in vec4 skylight_observer;  // network input at the observer / E\n"
       "layout(location = 2) in vec4 skylight_probe;     // network input at the surface point\n"
       "layout(location = 3) in vec2 skylight_weights;   // 1, or 0 where the view ray is in "
       "shadow\n"
       "layout(location = 4) in vec3 skylight_transmittance;\n"
       "layout(location = 5) in vec3 skylight_reflected;\n";
  s += flat ? "flat out vec3 skylight_colour;\n" : "out vec3 skylight_colour;\n";
  s += "void main() {\n"
       "  gl_Position = skylight_clip;\n"
       "  vec3 c = skylight_reflected;\n"
       "  if (skylight_weights.x != 0.0) c += skylight_weights.x * "
       "skylight_pietras(skylight_observer);\n"
       "  if (skylight_weights.y != 0.0)\n"
       "    c -= skylight_weights.y * skylight_transmittance * skylight_pietras(skylight_probe);\n"
       "  skylight_colour = max(c, vec3(0.0));\n"
       "}\n";
  return s;
}

std::string planet_fragment_shader(bool flat) {
  std::string s(kGlslVersion);
  s += flat ? "flat in vec3 skylight_colour;\n" : "in vec3 skylight_colour;\n";
  s += "out vec4 colour;\nvoid main() {\n  colour = vec4(skylight_colour, 1.0);\n}\n";
  return s;
}

PlanetRenderer::PlanetRenderer(const nn::PietrasNetwork& net, int width, int height)
    : program_(planet_vertex_shader(net, false), planet_fragment_shader(false)),
      target_(width, height) {}

void PlanetRenderer::draw(const PlanetMesh& mesh) {
  Attributes a;
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) a.add(mesh.clip[i], mesh.vertices[i]);
  target_.clear();
  const auto spans = a.spans();
  target_.draw_mesh(program_, spans, mesh.indices);
}

io::ImageF PlanetRenderer::read() const {
  return target_.read(4);
}

io::ImageF render_planet(const nn::PietrasNetwork& net, const PlanetMesh& mesh, int width,
                         int height) {
  PlanetRenderer r(net, width, height);
  r.draw(mesh);
  return r.read();
}

std::vector<float> shade_planet_vertices_gpu(const nn::PietrasNetwork& net,
                                             const PlanetMesh& mesh) {
  const std::size_t n = mesh.vertices.size();
  std::vector<float> out(3 * n);
  if (n == 0) return out;
  const std::size_t w = std::min(n, kVertexRowWidth), h = (n + w - 1) / w;
  Attributes a;
  std::vector<unsigned> indices;
  // A triangle around the centre of pixel (col, row) that contains no other pixel centre.
  constexpr double kCorner[3][2] = {{-0.4, -0.4}, {0.6, -0.4}, {-0.4, 0.6}};
  for (std::size_t i = 0; i < n; ++i) {
    const double col = static_cast<double>(i % w) + 0.5;
    const double gl_row = static_cast<double>(h - 1 - i / w) + 0.5;  // GL rows count upwards
    for (const auto& k : kCorner) {
      indices.push_back(static_cast<unsigned>(a.weights.size() / 2));
      a.add({2.0 * (col + k[0]) / static_cast<double>(w) - 1.0,
             2.0 * (gl_row + k[1]) / static_cast<double>(h) - 1.0, 0.0, 1.0},
            mesh.vertices[i]);
    }
  }
  const io::ImageF img = draw(net, a, indices, static_cast<int>(w), static_cast<int>(h), true);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < 3; ++k) out[3 * i + k] = img.data[4 * i + k];
  return out;
}

PlanetFrame render_planet_view(const nn::PietrasNetwork& net, const PlanetViewOptions& f) {
  const NishitaParameters planet = nishita_parameters_of(net);
  const SunPosition sun = sun_from_degrees(f.sun_zenith_deg, f.sun_azimuth_deg);
  PlanetFrame frame;
  frame.altitude_m = f.altitude(planet.ground_radius_m);
  PlanetView view = f.orbit ? orbit_view(planet, frame.altitude_m, sun.zenith)
                            : ground_view(planet, frame.altitude_m, sun.zenith, sun.azimuth,
                                          deg_to_rad(f.look_elevation_deg));
  if (const auto fov = f.vertical_fov_deg()) view.vertical_fov = deg_to_rad(*fov);
  view.albedo = f.albedo;
  view.subdivisions = f.subdivisions;
  view.width = f.width;
  view.height = f.height;
  const auto seconds_since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  };
  const auto t0 = std::chrono::steady_clock::now();
  const NishitaSampler atmosphere(planet);
  const PlanetMesh mesh = planet_mesh(net, atmosphere, view);
  frame.mesh_seconds = seconds_since(t0);
  frame.vertices = mesh.vertices.size();
  frame.triangles = mesh.indices.size() / 3;
  Context context;
  frame.renderer = context.renderer();
  const auto t1 = std::chrono::steady_clock::now();
  const io::ImageF rgba = render_planet(net, mesh, f.width, f.height);
  frame.gl_seconds = seconds_since(t1);
  frame.rgb = io::ImageF(f.width, f.height, 3);
  for (std::size_t i = 0; i < frame.rgb.data.size() / 3; ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      const float v = rgba.data[4 * i + k];
      frame.rgb.data[3 * i + k] = std::isfinite(v) ? v : 0.0f;
    }
  return frame;
}

}  // namespace skylight::gpu
