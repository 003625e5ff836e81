#!/usr/bin/python3
"""Writes data/haze_scene/: a synthetic clear-day valley photo with its depth map, for the README's
quick start and docs/HAZE.md (`skylight haze add|remove`). Deterministic: the same files on every
run (data/haze_scene/PROVENANCE.md records their sha256).

The scene, seen by a pinhole camera 60 m above a valley floor (vertical field of view 30 deg,
heading 200 deg, pitch 2 deg: `haze ... --vfov 30 --heading 200 --pitch 2`):
- the sky: skylight's own Hosek-Wilkie sky (`skylight eval --model hosek --turbidity 2`, sun at
  zenith 40 deg, azimuth 150 deg), linear sRGB with Y in cd/m^2, evaluated for each pixel's view
  direction;
- five ridges at horizontal distances 0.8, 2.5, 6, 14 and 30 km, their crest heights sums of
  sines of the azimuth, and a meadow in front of the first: Lambertian vegetation and rock (albedo
  0.03-0.12, snow 0.7 on the farthest crests) under 85 000 lux (L = albedo E / pi), with slopes
  towards the sun lighter and a 5 % grain, and no haze at all (what `haze add` starts from);
- the depth: the distance along each pixel's ray to what it sees [m]; 100 km for the sky.

Usage: scripts/make_haze_scene.py [SKYLIGHT_BINARY] (default build/skylight). Needs python3-numpy.
"""
import math
import pathlib
import struct
import subprocess
import sys

import numpy as np

WIDTH, HEIGHT = 320, 160
VFOV_DEG, HEADING_DEG, PITCH_DEG = 30.0, 200.0, 2.0
OBSERVER_M = 60.0  # above the valley floor
SKY_DEPTH_M = 100_000.0
ILLUMINANCE_LUX = 85_000.0
# (horizontal distance [m], crest height above the observer [m], crest amplitude [m], albedo RGB)
RIDGES = [
    (800.0, -20.0, 40.0, (0.05, 0.08, 0.035)),
    (2_500.0, 80.0, 120.0, (0.045, 0.07, 0.035)),
    (6_000.0, 250.0, 250.0, (0.06, 0.07, 0.045)),
    (14_000.0, 1_500.0, 500.0, (0.08, 0.08, 0.07)),
    (30_000.0, 3_500.0, 900.0, (0.11, 0.11, 0.12)),
]
MEADOW_ALBEDO = (0.06, 0.09, 0.03)
SNOW_LINE_M, SNOW_ALBEDO = 3_600.0, 0.7  # above the observer


def view_directions():
    """East-North-Up unit vectors of the pixels' centres (gluPerspective, docs/HAZE.md)."""
    h, p = math.radians(HEADING_DEG), math.radians(PITCH_DEG)
    forward = np.array([math.sin(h) * math.cos(p), math.cos(h) * math.cos(p), math.sin(p)])
    right = np.array([math.cos(h), -math.sin(h), 0.0])
    up = np.cross(right, forward)
    ty = math.tan(math.radians(VFOV_DEG) / 2)
    tx = ty * WIDTH / HEIGHT
    col = (np.arange(WIDTH) + 0.5) / WIDTH * 2 - 1
    row = 1 - (np.arange(HEIGHT) + 0.5) / HEIGHT * 2
    x, y = np.meshgrid(col * tx, row * ty)
    d = x[..., None] * right + y[..., None] * up + forward
    return d / np.linalg.norm(d, axis=-1, keepdims=True)


def crest(azimuth, index, height, amplitude):
    """Crest height of ridge `index` above the observer at these azimuths [rad]."""
    a = azimuth + 0.7 * index
    return height + amplitude * (0.5 * np.sin(3 * a) + 0.3 * np.sin(7 * a + 1.3) + 0.2 * np.sin(17 * a))


def shading(azimuth, elevation, index, height, amplitude, dist):
    """Light on a ridge's slopes: slopes turned towards the sun (azimuth 150 deg) brighter, the
    foot of each ridge darker than its crest, and a 5 % grain (fixed seed)."""
    a = azimuth + 0.7 * index
    slope = 1.5 * np.cos(3 * a) + 2.1 * np.cos(7 * a + 1.3) + 3.4 * np.cos(17 * a)
    facing = np.sin(azimuth - math.radians(150.0))
    low = height - amplitude
    rise = np.clip((np.tan(elevation) * dist - low) / (2 * amplitude), 0, 1)
    grain = np.random.default_rng(index).uniform(-1, 1, elevation.shape)
    return (0.8 + 0.25 * np.tanh(slope * facing)) * (0.7 + 0.3 * rise) * (1 + 0.05 * grain)


def sky_rgb(skylight, dirs):
    zen = np.degrees(np.arccos(np.clip(dirs[..., 2], -1, 1))).ravel()
    azi = np.degrees(np.arctan2(dirs[..., 0], dirs[..., 1])).ravel() % 360
    csv = "zenith_deg,azimuth_deg\n" + "".join(f"{z:.9g},{a:.9g}\n" for z, a in zip(zen, azi))
    out = subprocess.run(
        [skylight, "eval", "--model", "hosek", "--turbidity", "2", "--sun-zenith", "40",
         "--sun-azimuth", "150"], input=csv, capture_output=True, text=True, check=True).stdout
    rows = np.loadtxt(out.splitlines()[1:], delimiter=",")
    return rows[:, 2:5].reshape(HEIGHT, WIDTH, 3)


def write_rgbe(path, rgb):
    """Radiance .hdr, flat (uncompressed) scanlines, top row first."""
    m = rgb.max(axis=-1)
    e = np.zeros(m.shape, dtype=np.int32)
    mant = np.zeros(m.shape)
    pos = m > 1e-32
    mant[pos], e[pos] = np.frexp(m[pos])
    scale = np.where(pos, mant * 256.0 / np.where(pos, m, 1), 0)
    out = np.zeros(rgb.shape[:2] + (4,), dtype=np.uint8)
    out[..., :3] = np.clip(rgb * scale[..., None], 0, 255).astype(np.uint8)
    out[..., 3] = np.where(pos, e + 128, 0).astype(np.uint8)
    header = f"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {HEIGHT} +X {WIDTH}\n".encode()
    path.write_bytes(header + out.tobytes())


def write_pfm(path, depth):
    """One-channel PFM (Pf), little-endian, bottom row first."""
    header = f"Pf\n{WIDTH} {HEIGHT}\n-1.0\n".encode()
    path.write_bytes(header + np.ascontiguousarray(depth[::-1], dtype="<f4").tobytes())


def main():
    skylight = sys.argv[1] if len(sys.argv) > 1 else "build/skylight"
    out_dir = pathlib.Path(__file__).resolve().parent.parent / "data" / "haze_scene"
    out_dir.mkdir(exist_ok=True)
    dirs = view_directions()
    azimuth = np.arctan2(dirs[..., 0], dirs[..., 1])
    elevation = np.arcsin(np.clip(dirs[..., 2], -1, 1))
    rgb = sky_rgb(skylight, dirs)
    depth = np.full((HEIGHT, WIDTH), SKY_DEPTH_M)
    lit = ILLUMINANCE_LUX / math.pi  # cd/m^2 per unit albedo
    # From the farthest ridge to the meadow, each nearer surface drawn over the farther ones.
    for index, (dist, height, amp, albedo) in reversed(list(enumerate(RIDGES))):
        hidden = np.tan(elevation) * dist < crest(azimuth, index, height, amp)
        ray = dist / np.cos(elevation)
        depth[hidden] = ray[hidden]
        light = lit * shading(azimuth, elevation, index, height, amp, dist)
        # Snow on the farthest ridge's crests.
        snow = np.tan(elevation) * dist > SNOW_LINE_M if index == len(RIDGES) - 1 else False
        for c in range(3):
            rgb[..., c][hidden] = (np.where(snow, SNOW_ALBEDO, albedo[c]) * light)[hidden]
    meadow = np.where(elevation < 0, OBSERVER_M / np.maximum(np.sin(-elevation), 1e-9), np.inf)
    ground = meadow < depth
    depth[ground] = meadow[ground]
    grass = lit * shading(azimuth, elevation, len(RIDGES), -OBSERVER_M, 0.5 * OBSERVER_M, 1000.0)
    for c in range(3):
        rgb[..., c][ground] = (MEADOW_ALBEDO[c] * grass)[ground]
    write_rgbe(out_dir / "valley.hdr", rgb)
    write_pfm(out_dir / "valley_depth.pfm", depth.astype(np.float32))
    print(f"wrote {out_dir}/valley.hdr and valley_depth.pfm ({WIDTH} x {HEIGHT}); "
          f"depth {depth.min():.0f} .. {depth[depth < SKY_DEPTH_M].max():.0f} m, sky {SKY_DEPTH_M:.0f} m")


if __name__ == "__main__":
    main()
