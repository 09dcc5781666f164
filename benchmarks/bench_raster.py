"""Time the NumPy reference back end on a 512x512 frame of a lit sphere.

The sphere is a 64 x 64-segment latitude/longitude grid (8192 triangles, half of them culled),
transformed by a hand-written vertex program (world-view-projection rows, dp4) and shaded per
pixel by a fragment program computing N.L diffuse plus a Blinn-Phong specular term.

    .venv/bin/python benchmarks/bench_raster.py [--frames N] [--threads T] [--profile]
"""
from __future__ import annotations

import argparse
import cProfile
import pstats
import time

import numpy as np

from effects.program.backend import create_backend
from effects.program.ir import Builder
from effects.program.passprogram import PassProgram


def sphere_grid(segments: int = 64) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """Unit-sphere positions and normals on a (segments+1)^2 grid, and its triangle list,
    wound clockwise as seen from outside (D3D's front faces)."""
    theta = np.linspace(0, np.pi, segments + 1)
    phi = np.linspace(0, 2 * np.pi, segments + 1)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    n = np.stack([np.sin(t) * np.cos(p), np.cos(t), np.sin(t) * np.sin(p)], -1).reshape(-1, 3)
    i = (np.arange(segments)[:, None] * (segments + 1) + np.arange(segments)[None, :]).ravel()
    a, b, c, d = i, i + 1, i + segments + 1, i + segments + 2
    tris = np.concatenate([np.stack([a, b, c], 1), np.stack([b, d, c], 1)])
    streams = {"position": n.astype(np.float32), "normal": n.astype(np.float32)}
    return streams, tris


def view_projection(eye_z: float = -3.2, fov_deg: float = 45.0, near: float = 0.1,
                    far: float = 10.0) -> np.ndarray:
    """clip = M @ [x, y, z, 1] for a left-handed camera at (0, 0, eye_z) looking down +z
    (D3DXMatrixPerspectiveFovLH: view z' = z - eye_z, clip z = q z' - q near, w = z')."""
    f = 1 / np.tan(np.radians(fov_deg) / 2)
    q = far / (far - near)
    return np.array([[f, 0, 0, 0], [0, f, 0, 0], [0, 0, q, -q * near - q * eye_z],
                     [0, 0, 1, -eye_z]], np.float64)


def lit_sphere_pass() -> PassProgram:
    vb = Builder("vertex")
    pos = vb.varying("position", components=3)
    rows = [vb.uniform(f"wvp{i}") for i in range(4)]
    clip = vb.const(0.0)
    for i, r in enumerate(rows):
        clip = vb.merge(clip, vb.dp4(pos, r), "xyzw"[i])
    vb.output("position", clip)
    vb.output("texcoord0", vb.varying("normal", components=3))
    vb.output("texcoord1", pos)
    fb = Builder("fragment")
    n = fb.nrm(fb.varying("texcoord0"))
    world = fb.varying("texcoord1")
    light = fb.uniform("light_dir")
    eye = fb.uniform("eye")
    v = fb.nrm(fb.sub(eye, world))
    h = fb.nrm(fb.add(v, light))
    ndl = fb.saturate(fb.dp3(n, light))
    ndh = fb.saturate(fb.dp3(n, h))
    spec = fb.pow(ndh, fb.const(32.0))
    diffuse = fb.mul(fb.uniform("diffuse"), ndl)
    fb.output("color0", fb.saturate(fb.add(diffuse, spec)))
    m = view_projection()
    uniforms = {f"wvp{i}": m[i] for i in range(4)}
    uniforms.update(light_dir=(0.577, 0.577, -0.577, 0), eye=(0, 0, -3.2, 1),
                    diffuse=(0.8, 0.3, 0.2, 1))
    return PassProgram(fb.build(), vb.build(), uniforms=PassProgram.pack_uniforms(uniforms))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=10)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--profile", action="store_true")
    args = parser.parse_args()
    streams, tris = sphere_grid()
    program = lit_sphere_pass()
    backend = create_backend("numpy", threads=args.threads)

    def frame():
        backend.begin_frame((args.size, args.size), clear_color=(0, 0, 0, 1))
        backend.draw(program, streams, tris, "list", {})
        return backend.end_frame()

    image = frame()  # warm up
    times, cpu = [], []
    for _ in range(args.frames):
        start, start_cpu = time.perf_counter(), time.process_time()
        frame()
        times.append(time.perf_counter() - start)
        cpu.append(time.process_time() - start_cpu)
    lit = int((image[..., :3].max(axis=2) > 0).sum())
    # CPU time (all threads) is the steadier figure on a shared machine.
    print(f"{args.size}x{args.size} lit sphere, {len(tris)} triangles, {lit} lit pixels, "
          f"{args.threads} thread(s): median {1000 * np.median(times):.1f} ms, best "
          f"{1000 * min(times):.1f} ms per frame (CPU {1000 * np.median(cpu):.1f} ms)")
    if args.profile:
        cProfile.runctx("for _ in range(5): frame()", globals(), locals(), "/tmp/bench_raster.prof")
        pstats.Stats("/tmp/bench_raster.prof").sort_stats("tottime").print_stats(15)


if __name__ == "__main__":
    main()
