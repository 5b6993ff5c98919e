"""A random policy driving one robot, with a picture of the arena at the end.

    python python/examples/random_driver.py [out.png]
"""

import struct
import sys
import zlib

import gymnasium
import numpy as np

import vivae  # noqa: F401  (registers vivae/Drive-v0)



def write_png(path: str, rgb: np.ndarray) -> None:
    """An RGB image (height x width x 3, uint8) as a PNG file, without Pillow."""
    h, w, _ = rgb.shape
    rows = b"".join(b"\x00" + rgb[y].tobytes() for y in range(h))

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    header = struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


env = gymnasium.make("vivae/Drive-v0", scenario="roads", sensors="3x5", render_mode="rgb_array")
obs, info = env.reset(seed=0)
env.action_space.seed(0)
total = 0.0
while True:
    obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
    total += reward
    if terminated or truncated:
        break
print(f"{info['step']} steps, {total:.1f} px driven: average speed {total / info['step']:.3f} px/step")

image = env.render()
print(f"rendered {image.shape[1]}x{image.shape[0]} px")
if len(sys.argv) > 1:
    write_png(sys.argv[1], image)
    print(f"figure: {sys.argv[1]}")
