// The photo of the estimate benchmark, shared by bench/bench_models.cpp (EstimateFisheye1Mpx) and
// `skylight bench --estimate` (src/cli/bench_cmd.cpp): a 1024 x 1024 equidistant fisheye Preetham
// sky (T = 4, sun at 40 deg zenith / 150 deg azimuth) with the solar disc, as `render` draws it.
#pragma once

#include "skylight/core/camera.h"
#include "skylight/core/math.h"
#include "skylight/io/image.h"
#include "skylight/models/sky_model.h"
#include "skylight/render/sky_render.h"

namespace skylight::bench {

struct EstimateFixture {
  io::ImageF photo;
  Camera camera;
};

inline EstimateFixture estimate_fixture() {
  render::RenderSettings s;
  s.projection = Projection::fisheye;
  s.width = s.height = 1024;
  s.sun = SunMode::sky_and_sun;
  SkyParameters p;
  p.sun = {deg_to_rad(40.0), deg_to_rad(150.0)};
  p.values.set("turbidity", 4.0);
  return {render::render_sky(*make_sky_model("preetham", p), s).rgb,
          Camera{Projection::fisheye, 1024, 1024, {}}};
}

}  // namespace skylight::bench
