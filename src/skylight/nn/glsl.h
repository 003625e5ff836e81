// GLSL export of networks (docs/GPU.md): any nn::Mlp as a GLSL function with its weights baked
// in, and a neural sky network (sky_network.h) as a sky function. Plain text generation, no GL:
// it lives in nn/ so that `skylight nn export --glsl` works in a build without the gpu/ module,
// and gpu/ (which runs the shaders) depends on it, not the other way round.
//
// The code is GLSL 3.30 core (a subset that GLSL ES 3.00 also accepts: no double, no
// implicit int-to-float conversions). Weights are rounded once to single precision, printed
// with 9 significant digits (exact round trip of a float) and the layers unrolled: one
// expression per neuron, o^k_j = f_k(sum_i w^k_{j i} o^(k-1)_i + w^k_{j 0}) (mlp.h, eq. 5 of
// Satilmis et al. 2016), summed in input order starting from the bias.
#pragma once

#include <string>
#include <string_view>

#include "skylight/nn/mlp.h"
#include "skylight/nn/pietras.h"
#include "skylight/nn/sky_network.h"

namespace skylight::nn {

// The GLSL body of f(x) for an activation, x a float expression of a variable (e.g. "x"). The
// forms avoid overflow like activate() (mlp.h): sigmoid, tanh and the Pietras function go through
// exp of -|x|.
std::string glsl_activation_function(Activation a);
// Name of the helper function emitted for an activation: "skylight_act_<name>".
std::string glsl_activation_name(Activation a);

// The helper functions of every activation `net` uses, then
//   void <name>(in float x[n_0], out float y[n_L])
// computing Psi(x) (mlp.h). `name` must be a GLSL identifier (InvalidArgument otherwise).
std::string glsl_mlp(const Mlp& net, std::string_view name);

// A Pietras network (pietras.h) as GLSL (no #version line): the sub-networks as functions
// skylight_pietras_0, _1, ... and
//   vec3 skylight_pietras(vec4 x)
// = PietrasNetwork::rgb for x = (cos alpha0, cos beta0, cos theta0, rho0): the decoding of
// decode_pietras in single precision. The night bound of rgb_at is the caller's (gpu/planet.h).
std::string glsl_pietras_network(const PietrasNetwork& net);
// glsl_pietras_network, then PietrasNetwork::lit and rgb_at in GLSL (no #version line), the
// network's planet (R0, the atmosphere's top, H0) baked in:
//   bool skylight_pietras_lit(float altitude, float cos_view_zenith, float cos_view_sun,
//                             float cos_sun_zenith)
//   vec3 skylight_pietras_at(float altitude, vec3 view, vec3 sun)
// (altitude in m; view and sun unit vectors in the observer's frame, z up). The shadow test is
// view_ray_lit's, written in altitudes (r^2 - R0^2 = h (2 R0 + h)) so that single precision
// does not cancel: its decisions move by under a metre of the shadow's edge.
std::string glsl_pietras_sky(const PietrasNetwork& net);
// A complete GLSL compilation unit for `skylight nn export --glsl` of a Pietras file: a comment
// naming the network, "#version 330 core" and glsl_pietras_sky.
std::string glsl_pietras_network_file(const PietrasNetwork& net);

// A sky network as GLSL (no #version line; glsl_sky_network_file adds it):
//   vec3 skylight_sky_state(vec3 view, float sun_zenith, float sun_azimuth, float turbidity)
//     = SkyNetwork::rgb for state (turbidity, sun zenith, sun azimuth) and a unit view (ENU,
//     world frame): the input vector of compute_inputs (dataset.h; the rotation of Satilmis
//     et al. 2016 eq. 10), the network (function skylight_sky_network), the output encoding
//     decoded and times target_scale; 0 below the horizon (view.z < 0);
//   vec3 skylight_sky(vec3 view, vec3 sun, float turbidity)
//     the same with the sun as a unit vector (its azimuth is taken as pi, the paper's training
//     azimuth, when the sun is at the zenith).
// The network's state inputs (sqrt t, theta_sun, ...) are taken as given: pass turbidity 0 for
// a network trained on a source without turbidity, as NeuralSkyModel does.
std::string glsl_sky_network(const SkyNetwork& sky);
// A complete GLSL compilation unit for `skylight nn export --glsl`: a comment naming the network
// (architecture, inputs, encoding, provenance), "#version 330 core" and glsl_sky_network. A
// program links it with a fragment (or vertex) shader that calls skylight_sky.
std::string glsl_sky_network_file(const SkyNetwork& sky);

}  // namespace skylight::nn
