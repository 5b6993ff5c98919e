#!/usr/bin/env python3
"""Developer estimate (not part of CI): the share of a surface read's lane
batches whose sensors fall within at most 1, 2 or 4 of the raster's 8 x 8
tiles, for robots at random poses on a 1-pixel raster, sensors placed as
`SurfaceSensors` places them (rings from d_min to d_max, angles across the
field of view, angle the fast index). docs/benchmarks.md quotes it for the
idea of looking ids up in whole tiles instead of gathering them.

    python3 scripts/tile-hit-rates.py
"""
import math
import random


def places(rings, angles, d_min=10.0, d_max=50.0, fov=180.0):
    """`SurfaceSensors::places` and `sensors::spread`: one ring sits midway,
    one angle looks straight ahead."""
    out = []
    for r in range(rings):
        d = (d_min + d_max) / 2 if rings == 1 else d_min + (d_max - d_min) * r / (rings - 1)
        for a in range(angles):
            ang = 0.0 if angles == 1 else math.radians(fov) * (a / (angles - 1) - 0.5)
            out.append((d * math.cos(ang), d * math.sin(ang)))
    return out


def shares(rings, angles, lanes, poses, rng):
    sensors = places(rings, angles)
    within = {1: 0, 2: 0, 4: 0}
    batches = 0
    for _ in range(poses):
        px, py = rng.uniform(100, 700), rng.uniform(100, 500)
        h = rng.uniform(-math.pi, math.pi)
        c, s = math.cos(h), math.sin(h)
        cells = [(int(px + c * x - s * y), int(py + s * x + c * y)) for x, y in sensors]
        for j in range(0, len(cells), lanes):
            tiles = {(cx >> 3, cy >> 3) for cx, cy in cells[j : j + lanes]}
            batches += 1
            for k in within:
                within[k] += len(tiles) <= k
    return {k: v / batches for k, v in within.items()}


def main():
    rng = random.Random(1)
    print("grid    lanes  within 1 / 2 / 4 tiles")
    for rings, angles, lanes in [(32, 96, 16), (32, 96, 8), (20, 60, 8), (20, 60, 16), (3, 5, 8)]:
        s = shares(rings, angles, lanes, 300, rng)
        print(f"{rings}x{angles:<5} {lanes:>5}  {s[1]:.0%} / {s[2]:.0%} / {s[4]:.0%}")


if __name__ == "__main__":
    main()
