"""Taking a controller to a robot from Python: an exported champion runs in
onnxruntime with vivae's wheel commands on a recorded episode (to 1e-9:
ONNX's MatMul sums in the runtime's order and its Exp is the runtime's, not
vivae's portable one, so the last bits may differ); the JSON artifact,
stepped in plain Python in vivae's order, matches to the bit, in either
precision (fast: f32 with a fused multiply-add); and frames
drive the controller as `vivae drive-image` does."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import vivae


def small_run(tmp_path: Path, extra: str = "") -> Path:
    config = tmp_path / "c.toml"
    config.write_text(
        "[experiment]\nseed = 7\ngenerations = 3\nsteps = 150\n\n[neat]\npopulation_size = 24\n" + extra
    )
    out = tmp_path / "run"
    vivae.evolve(config=config, out=out, progress=False)
    return out


def onnx_wheels(model: Path, sensors: np.ndarray) -> tuple[np.ndarray, int]:
    ort = pytest.importorskip("onnxruntime")
    session = ort.InferenceSession(str(model), providers=["CPUExecutionProvider"])
    nodes = session.get_inputs()[1].shape[1]
    state = np.zeros((1, nodes))
    wheels = []
    for x in sensors:
        w, state = session.run(["wheels", "next_state"], {"sensors": x[None, :], "state": state})
        wheels.append(w[0])
    return np.array(wheels), nodes


@pytest.mark.parametrize(
    "extra, grids",
    [
        ("", {}),
        ("", {"sensors": "8x16", "neurons": "5x5"}),
        ('\n[substrate]\nkind = "es-hyperneat"\n', {}),
        ("\n[surface_sensors]\nfov = 360.0\nangles = 8\n", {"sensors": "4x24"}),
    ],
)
def test_an_exported_champion_runs_in_onnxruntime_as_in_vivae(tmp_path, extra, grids):
    run = small_run(tmp_path, extra)
    model = tmp_path / "c.onnx"
    assert vivae.export(run, "onnx", model, **grids) == [str(model)]
    onnx = pytest.importorskip("onnx")
    m = onnx.load(str(model))
    onnx.checker.check_model(m, full_check=True)
    assert m.opset_import[0].version == 17
    meta = {p.key: p.value for p in m.metadata_props}
    sheets = json.loads(meta["vivae_geometry"])
    rec = vivae.record_episode(run, robot=1, steps=300, **grids)
    assert rec["sensors"].shape == (300, sum(len(s["places"]) for s in sheets))
    got, _ = onnx_wheels(model, rec["sensors"])
    worst = float(np.max(np.abs(got - rec["wheels"])))
    print(f"onnxruntime vs vivae, {extra!r} {grids}: largest difference {worst:.3e}")
    assert worst <= 1e-9
    assert np.any(rec["wheels"][:, 0] != rec["wheels"][:, 1]), "the robot never turns"


def test_a_fast_champion_runs_in_onnxruntime_in_float32(tmp_path):
    run = small_run(tmp_path)
    model = tmp_path / "fast.onnx"
    vivae.export(run, "onnx", model, precision="fast")
    onnx = pytest.importorskip("onnx")
    m = onnx.load(str(model))
    onnx.checker.check_model(m, full_check=True)
    assert m.graph.input[0].type.tensor_type.elem_type == onnx.TensorProto.FLOAT
    rec = vivae.record_episode(run, robot=1, steps=300, precision="fast")
    ort = pytest.importorskip("onnxruntime")
    session = ort.InferenceSession(str(model), providers=["CPUExecutionProvider"])
    state = np.zeros((1, session.get_inputs()[1].shape[1]), dtype=np.float32)
    got = []
    for x in rec["sensors"].astype(np.float32):
        w, state = session.run(["wheels", "next_state"], {"sensors": x[None, :], "state": state})
        got.append(w[0])
    worst = float(np.max(np.abs(np.array(got, dtype=np.float64) - rec["wheels"])))
    print(f"onnxruntime float32 vs vivae fast: largest difference {worst:.3e}")
    # MatMul's order and the runtime's expf against vivae's: float32 rounding apart.
    assert worst <= 1e-5
    assert np.any(rec["wheels"][:, 0] != rec["wheels"][:, 1]), "the robot never turns"


def json_step(net: dict, x: list[float], state: list[float]) -> list[float]:
    """One step as the JSON's `step` key says, with vivae's portable exp."""
    ni, nxt = net["inputs"], list(state)
    for k in net["order"]:
        s = net["bias"][k]
        for l in range(net["starts"][k], net["starts"][k + 1]):
            j = net["sources"][l]
            s += net["weights"][l] * (x[j] if j < ni else (state if net["synchronous"] else nxt)[j - ni])
        nxt[k] = 2.0 / (1.0 + portable_exp(-4.9 * s)) - 1.0
    state[:] = nxt
    return [state[net["wheels"][0]], state[net["wheels"][1]]]


def portable_exp(x: float) -> float:
    """vivae_neat::math::exp, operation for operation."""
    import struct

    if x == x:
        x = min(max(x, -708.0), 709.0)
    shift = 6755399441055744.0
    kf = x * 1.4426950408889634 + shift
    k = kf - shift
    r = x - k * struct.unpack("<d", struct.pack("<Q", 0x3FE62E42FEE00000))[0] - k * struct.unpack(
        "<d", struct.pack("<Q", 0x3DEA39EF35793C76)
    )[0]
    p = 1.0 / 479001600.0
    for c in [1 / 39916800, 1 / 3628800, 1 / 362880, 1 / 40320, 1 / 5040, 1 / 720, 1 / 120, 1 / 24, 1 / 6, 0.5, 1.0, 1.0]:
        p = p * r + c
    n = struct.unpack("<q", struct.pack("<d", kf))[0] & 0xFFFFFFFF
    n = n - (1 << 32) if n >= 1 << 31 else n
    return p * struct.unpack("<d", struct.pack("<Q", (n + 1023) << 52))[0]


def test_the_json_artifact_steps_to_vivaes_bits(tmp_path):
    run = small_run(tmp_path)
    out = tmp_path / "c.json"
    vivae.export(run, "json", out)
    doc = json.loads(out.read_text())
    assert doc["format"] == "vivae-controller" and doc["sheets"][0]["sensor"] == "surface"
    net = doc["net"]
    rec = vivae.record_episode(run, robot=0, steps=200)
    state = [0.0] * net["nodes"]
    for x, w in zip(rec["sensors"].tolist(), rec["wheels"].tolist()):
        assert json_step(net, x, state) == w


def fma_f32(x: float, y: float, z: float) -> float:
    """vivae_neat::precision::fma_f32: x*y + z rounded once to f32."""
    import struct

    def f32(v: float) -> float:
        with np.errstate(over="ignore"):
            return float(np.float32(v))

    def next_up(v: float) -> float:
        (b,) = struct.unpack("<I", struct.pack("<f", v))
        b = 1 if b & 0x7FFFFFFF == 0 else (b - 1 if b >> 31 else b + 1)
        return struct.unpack("<f", struct.pack("<I", b))[0]

    two128, big = 2.0**128, float(np.finfo(np.float32).max)
    xy, zw = x * y, z
    s = xy + zw
    r = f32(s)
    if r == s or s != s:
        return r
    inf = abs(r) == float("inf")
    if inf:
        other = -big if r < 0 else big
        other64 = other
    elif s > r:
        other = next_up(r)
        other64 = two128 if abs(other) == float("inf") else other
    else:
        other = -next_up(-r)
        other64 = -two128 if abs(other) == float("inf") else other
    lo, hi = (other64, two128 if s > 0 else -two128) if inf else (r, other64)
    if s != (lo + hi) * 0.5 or abs(s) == float("inf"):
        return r
    b = s - xy
    err = (xy - (s - b)) + (zw - b)
    if err == 0.0:
        return r
    toward = (err < 0.0) == (s > 0.0) if inf else (err > 0.0) == (other64 > r)
    return other if toward else r


def exp_f32(x: np.float32) -> np.float32:
    """vivae_neat::precision::exp_f32 (Cephes' expf), in float32 operations."""
    f = np.float32
    if x == x:
        x = min(max(x, f(-87.0)), f(88.0))
    shift = f(12582912.0)
    kf = x * f(1.442695) + shift
    k = kf - shift
    r = x - k * f(0.6933594) - k * f(-2.1219444e-4)
    q = f(1.9875691e-4)
    for c in [1.3981999e-3, 8.333452e-3, 4.1665796e-2, 1.6666666e-1, 0.5]:
        q = q * r + f(c)
    y = q * (r * r) + r + f(1.0)
    bits = (int(kf.view(np.uint32)) - (0x4B400000 - 127)) << 23 & 0xFFFFFFFF
    return y * np.uint32(bits).view(np.float32)


def json_step_fast(net: dict, x: list[float], state: list[float]) -> list[float]:
    """One step of a fast controller as the JSON's `step` key says: f32 throughout."""
    f = np.float32
    ni, nxt = net["inputs"], list(state)
    for k in net["order"]:
        s = float(f(net["bias"][k]))
        for l in range(net["starts"][k], net["starts"][k + 1]):
            j = net["sources"][l]
            v = x[j] if j < ni else state[j - ni]
            s = fma_f32(float(f(net["weights"][l])), float(f(v)), s)
        nxt[k] = float(f(2.0) / (f(1.0) + exp_f32(f(-4.9) * f(s))) - f(1.0))
    state[:] = nxt
    return [state[net["wheels"][0]], state[net["wheels"][1]]]


def test_a_fast_json_artifact_steps_to_vivaes_fast_bits(tmp_path):
    run = small_run(tmp_path)
    out = tmp_path / "fast.json"
    vivae.export(run, "json", out, precision="fast")
    net = json.loads(out.read_text())["net"]
    assert net["precision"] == "fast"
    assert all(float(np.float32(w)) == w for w in net["weights"] + net["bias"])
    rec = vivae.record_episode(run, robot=0, steps=200, precision="fast")
    exact = vivae.record_episode(run, robot=0, steps=200)
    assert np.all(rec["sensors"].astype(np.float32) == rec["sensors"]), "fast reads in f32"
    assert np.any(rec["wheels"] != exact["wheels"]), "the two precisions give other bits"
    state = [0.0] * net["nodes"]
    for x, w in zip(rec["sensors"].tolist(), rec["wheels"].tolist()):
        assert json_step_fast(net, x, state) == w
    with pytest.raises(ValueError, match="precision"):
        vivae.export(run, "json", out, precision="half")


def test_c_export_writes_the_file_and_its_header(tmp_path):
    run = small_run(tmp_path)
    written = vivae.export(run, "c", tmp_path / "ctl.c", generation=2)
    assert written == [str(tmp_path / "ctl.c"), str(tmp_path / "ctl.h")]
    header = (tmp_path / "ctl.h").read_text()
    assert "typedef double vivae_real;" in header
    assert "void vivae_step(const vivae_real *in, vivae_real *state, vivae_real *out);" in header
    vivae.export(run, "c", tmp_path / "fast.c", precision="fast")
    assert "typedef float vivae_real;" in (tmp_path / "fast.h").read_text()
    with pytest.raises(ValueError, match="generation 99"):
        vivae.export(run, "c", tmp_path / "x.c", generation=99)
    with pytest.raises(ValueError, match="onnx, c or json"):
        vivae.export(run, "png", tmp_path / "x.png")


def test_drive_image_reads_camera_frames_and_a_map_alike(tmp_path):
    run = small_run(tmp_path)
    # A map of grass with a road, coloured as vivae draws them.
    world = np.zeros((256, 256, 3), dtype=np.uint8)
    world[:, :] = (0x3A, 0x8A, 0x2E)
    world[100:180, 60:140] = (0x2B, 0x2B, 0x2B)
    poses = [(128, 128, 0.0), (100, 150, 0.0), (90, 120, 0.0), (150, 140, 0.0)]
    # Camera frames: the map cut around each pose, the robot in the middle.
    frames = [world[y - 64 : y + 64, x - 64 : x + 64].copy() for x, y, _ in poses]
    from_frames = vivae.drive_image(run, frames, radius=64)
    on_map = vivae.drive_image(run, [world], poses=poses)
    assert on_map == from_frames
    assert len(set(on_map)) > 1, "the road should change what the robot does"
    rgba = np.concatenate([world, np.full((256, 256, 1), 255, dtype=np.uint8)], axis=2)
    assert vivae.drive_image(run, [rgba], poses=poses) == on_map
    with pytest.raises(ValueError, match="channels"):
        vivae.drive_image(run, [np.zeros((4, 4, 2), dtype=np.uint8)])
