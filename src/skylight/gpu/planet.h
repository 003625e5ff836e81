// The Pietras vertex shader (Pietras §III-V, docs/PIETRAS.md): an icosphere planet and its
// atmosphere shell, every vertex shaded by the per-vertex network of nn/pietras.h in a GL vertex
// shader (nn/glsl.h's glsl_pietras_network), colours interpolated over the triangles.
//
// Per vertex V seen from the camera C along view = (V - C) / |V - C|, the evaluation point E is
// the observer C inside the atmosphere, or where the view ray enters the top sphere from outside.
// With E's zenith and altitude (models/pietras.h):
//  * shell vertex (radius of the top): the sky from E along the view, rgb_at(h_E, ...);
//  * ground vertex (radius R0): the surface colour of §IV, pietras_surface_terms(E, view, |V-E|,
//    albedo, sun): I = I(E) - T(E, V) I(V) + T(E, V) albedo/pi E_sun(V). Ground vertices facing
//    away from the camera are black (hidden by the front ones).
// The terms are computed on the CPU (PlanetMesh) and become vertex attributes; the shader
// evaluates the network twice and combines them. shade_planet_vertex is the CPU reference on the
// same terms. The shell is drawn at the far end of the depth range so that the ground covers it.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "skylight/core/colorimetry.h"
#include "skylight/core/frame.h"
#include "skylight/gpu/context.h"
#include "skylight/io/image.h"
#include "skylight/models/pietras.h"
#include "skylight/nn/pietras.h"

namespace skylight::gpu {

// A pinhole camera and the sun in the planet-centred frame (metres; the planet's centre at 0).
struct PlanetView {
  Vec3 camera_m{0.0, 0.0, 6361e3};
  Vec3 forward{0.0, 1.0, 0.0}, up{0.0, 0.0, 1.0};  // unit, orthogonal
  double vertical_fov = 60.0 * kDegree;            // [rad]
  Vec3 sun{0.0, 0.0, 1.0};                         // unit
  double albedo = 0.3;                             // grey Lambertian ground
  int subdivisions = 6;                            // icosphere level of both spheres
  int width = 640, height = 480;
};

// From orbit: the camera at `altitude_m` above the point (0, 0, R0) looking at the planet's centre
// with a field of view that frames the atmosphere; the sun at `sun_zenith` from that point's
// zenith (in the x-z plane).
PlanetView orbit_view(const NishitaParameters& planet, double altitude_m, double sun_zenith);
// From the ground: the camera at `altitude_m` above (0, 0, R0) looking north (+y) and
// `look_elevation` above the horizon; the sun at `sun_zenith` and `sun_azimuth` (from north
// towards east) there.
PlanetView ground_view(const NishitaParameters& planet, double altitude_m, double sun_zenith,
                       double sun_azimuth, double look_elevation = 10.0 * kDegree);

// One vertex's network inputs and §IV terms: colour = w_o rgb(observer) - T * w_p rgb(probe) +
// reflected, with w = 0 where the view ray is in shadow (PietrasNetwork::lit, as rgb_at) and
// rgb = rgb(input).
struct PlanetVertex {
  nn::PietrasInput observer, probe;
  double observer_weight = 0, probe_weight = 0;
  std::array<double, 3> transmittance{};
  Rgb reflected{};
};

struct PlanetMesh {
  std::vector<std::array<double, 4>> clip;  // clip-space positions
  std::vector<PlanetVertex> vertices;       // ground vertices first, then the shell's
  std::vector<unsigned> indices;            // 3 per triangle
  std::size_t ground_vertices = 0;
};

// Both spheres at view.subdivisions with their vertex terms (InvalidArgument for a camera below
// the ground or a bad view). `atmosphere` must be the network's planet (nishita_parameters_of).
PlanetMesh planet_mesh(const nn::PietrasNetwork& net, const NishitaSampler& atmosphere,
                       const PlanetView& view);
// The CPU reference of the vertex shader: the colour of one vertex (double precision).
Rgb shade_planet_vertex(const nn::PietrasNetwork& net, const PlanetVertex& v);

// The vertex and fragment shaders. flat: no interpolation (each fragment takes its provoking
// vertex's colour exactly), for the per-vertex comparison.
std::string planet_vertex_shader(const nn::PietrasNetwork& net, bool flat);
std::string planet_fragment_shader(bool flat);

// Frames of one network at one size: the program compiled and the target made once, so a frame
// costs the attribute upload and the draw (and the readback when read). Needs a current Context,
// which it must not outlive.
class PlanetRenderer {
 public:
  PlanetRenderer(const nn::PietrasNetwork& net, int width, int height);
  // Uploads the mesh's vertex attributes and draws it (no readback; Context::finish to wait).
  void draw(const PlanetMesh& mesh);
  // The last frame, as render_planet returns it.
  io::ImageF read() const;

 private:
  Program program_;
  Target target_;
};

// The frame: linear sRGB in r, g, b, alpha 1 where a triangle was drawn, 0 elsewhere (space).
// Needs a current Context.
io::ImageF render_planet(const nn::PietrasNetwork& net, const PlanetMesh& mesh, int width,
                         int height);
// The vertex shader's colour of every vertex, read back exactly: vertex i is drawn as a flat
// triangle covering only the centre of pixel (i % W, i / W) of a W-wide target. Needs a current
// Context. Returns r, g, b per vertex.
std::vector<float> shade_planet_vertices_gpu(const nn::PietrasNetwork& net, const PlanetMesh& mesh);

// `nn planet`: the network's planet (its training planet, nishita_parameters_of) seen as the
// options say, from orbit or from the ground, in a context of its own: the linear sRGB frame
// (space black), the vertex terms' CPU time and the GL draw's.
PlanetFrame render_planet_view(const nn::PietrasNetwork& net, const PlanetViewOptions& options);

}  // namespace skylight::gpu
