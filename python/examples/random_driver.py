"""A random policy driving one robot, with a picture of the arena at the end.

    python python/examples/random_driver.py [out.png]
"""

import sys

import gymnasium
import numpy as np

import vivae  # noqa: F401  (registers vivae/Drive-v0)

env = gymnasium.make("vivae/Drive-v0", scenario="roads", sensors="3x5", render_mode="rgb_array")
obs, info = env.reset(seed=0)
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
    try:
        from PIL import Image

        Image.fromarray(image).save(sys.argv[1])
        print(f"figure: {sys.argv[1]}")
    except ImportError:
        np.save(sys.argv[1] + ".npy", image)
        print(f"(Pillow not installed) pixels: {sys.argv[1]}.npy")
