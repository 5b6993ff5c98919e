"""bench.py's DoublePoleMarkov under three fixed linear controllers (see physics_check.sh)."""
import sys
import jax
if sys.argv[1] == "x64":
    jax.config.update("jax_enable_x64", True)
import jax.numpy as jnp
import os
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench
env = bench.DoublePoleMarkov()
ws = [[0.5, 0.8, 3.0, 0.6, -2.0, 0.1, 0.0],
      [0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0],
      [1.2, 1.5, 6.0, 1.1, -4.0, -0.3, -0.05]]
for w in ws:
    w = jnp.array(w)
    def cond(c):
        obs, s, done, t, s50 = c
        return (~done) & (t < 100_000)
    def body(c):
        obs, s, done, t, s50 = c
        a = bench.steep_sigmoid(jnp.dot(w, obs))
        obs, s, r, failed, _ = env.env_step(None, s, a)
        t2 = t + jnp.where(failed, 0, 1)
        s50 = jnp.where(t2 == 3, s, s50)
        return obs, s, failed, t2, s50
    obs, s = env.env_reset(None)
    _, sf, _, t, s50 = jax.jit(lambda o, s: jax.lax.while_loop(cond, body, (o, s, False, 0, s)))(obs, s)
    print(f"steps={int(t)} state3={[float(x) for x in s50]} final={[float(x) for x in sf]}")
