// The GL frames of `skylight bench` (--models gpu, --haze), timed against the CPU paths of the
// same work (perf/workloads.h): the nn model's and a log3 Pietras network's fragment-shader frame,
// the Pietras planet by vertex shader, and the haze retarget frame (docs/GPU.md).
#pragma once

#include "skylight/perf/bench.h"

namespace skylight::gpu {

// A width x height equirect frame of each network against its CPU batch path on all threads
// (draw + glFinish, and with the float readback), then the planet. Needs EGL (GpuError).
void bench_frames(int width, int height, int repeats, const perf::Output& out);
// The haze retarget frame (1920 x 1080) by the fragment shader against `cpu_wall_s`, the CPU
// path's wall time per frame; says so when there is no headless GL.
void bench_haze(int repeats, double cpu_wall_s, const perf::Output& out);

}  // namespace skylight::gpu
