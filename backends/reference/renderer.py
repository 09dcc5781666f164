"""The NumPy reference back end: the ground truth every other back end is compared with.

A draw runs the vertex program over all vertices at once, sets the triangles up once (clip,
project, cull: `rasterize.setup_triangles`), then works band by band of pixel rows: rasterises
the band into 2x2 quads, runs the fragment program over every quad row with sampler callbacks
that see whole quads (`sampler`), and merges the band's covered, unkilled fragments into the
render target in draw order (`output`). Bands hold disjoint pixels, so they are shaded and
merged on a small thread pool (NumPy releases the GIL inside its kernels) in any order, and a
band's size, not the frame's, bounds the memory a draw takes beyond the frame's own buffers.
Helper pixels are shaded only when the fragment program samples a texture.

Conventions beyond `effects.program.backend`:
- Vertex colour outputs (color0, color1) are saturated before interpolation
  (docs/reference/semantics.md section 0); with no vertex program the colour streams are
  saturated too.
- A varying the fragment program reads but nothing supplies reads as D3D's vertex defaults:
  color0 (1, 1, 1, 1), color1 (0, 0, 0, 0), anything else (0, 0, 0, 1). The same defaults fill
  vertex-program inputs missing from `streams`.
- Fragment builtins: 'vpos' (pixel x, y, 0, 1; D3D9 pixel centres are integers) and 'vface'
  (+1 front, -1 back, replicated).
- Fog and the fixed-function specular add are not applied here: lowering folds both into the
  programs (`effects.lower.passes`), so the fragment program's colour is final.
- The fragment 'depth' output (oDepth) replaces the interpolated depth, saturated.
- ShadeMode = Phong with `PassProgram.lighting`: the lit diffuse and specular the fragment
  program names are shaded by Bishop and Weimer's Taylor form (`taylor_lighting`) and given
  to the program in place of its exact normalised-normal lighting (which GL draws).
"""
from __future__ import annotations

import ctypes
import sys
from concurrent.futures import ThreadPoolExecutor
from typing import Mapping

import numpy as np

from effects.program.ir import OPS, Program
from effects.program.passprogram import PassProgram, TextureBinding

from effects.program.backend import DrawError, register_backend, triangle_list
from backends.reference import output
from backends.reference.evaluate import evaluate, input_components
from backends.reference import taylor_lighting
from backends.reference.rasterize import (SUBPIXEL_BITS, QuadFragments, TriangleSetup,
                                          setup_triangles)
from backends.reference.sampler import SamplerSettings, gradient_lod, sample

_COLOR_VARYINGS = ("color0", "color1")
_DEFAULTS = {"color0": np.ones(4, np.float32), "color1": np.zeros(4, np.float32)}
_DEFAULT_VALUE = np.array([0, 0, 0, 1], np.float32)
_CHUNK_ROWS = 4 * 8192       # rows shaded per chunk, whole quads (temporaries stay small)
BAND_PIXELS = 1 << 16        # pixels per band of rows: bounds a band's fragments (~7 MiB of
                             # them at the ~110 bytes a fragment costs in flight)
PARALLEL_PIXELS = 1 << 15    # the smallest band worth a thread of its own: a band has fixed
                             # costs (its NumPy calls, the GIL held between them), and phong.fx
                             # on 2 threads against 1 took 1.9x at 2k-pixel bands, 1.55x at 8k,
                             # 1.4x at 18k, 0.95x at 32k, 0.9x at 64k (2-core VM, 2026-12-02)


def band_rows(size: tuple[int, int], threads: int = 1) -> list[tuple[int, int]]:
    """Row ranges [y0, y1) that cover a frame: about BAND_PIXELS each, and at least one per
    thread where each would still hold PARALLEL_PIXELS; every band starts on an even row, so
    2x2 quads are never cut."""
    width, height = size
    bands = -(-width * height // BAND_PIXELS)
    if threads > 1:
        bands = max(bands, min(threads, width * height // PARALLEL_PIXELS))
    rows = max(2, -(-height // max(1, bands)))
    rows += rows % 2
    return [(y0, min(y0 + rows, height)) for y0 in range(0, height, rows)]


def sampler_settings(binding: TextureBinding) -> SamplerSettings:
    """The lookup settings of a texture binding's sampler states."""
    return SamplerSettings(binding.address_u, binding.address_v, binding.address_w,
                           tuple(binding.border_color), binding.min_filter, binding.mag_filter,
                           binding.mip_filter, binding.mip_lod_bias, binding.max_mip_level)


def sampler_callbacks(program: PassProgram, textures: Mapping[str, object],
                      stage: Program | None = None) -> dict:
    """Sampler index -> callback(coord, kind=, bias=, lod=) for every bound slot the program
    `stage` (the fragment program by default; the vertex program for vertex textures) samples.
    The texture's own kind decides the lookup; unbound slots get no callback (the evaluator
    reads (0, 0, 0, 1) there)."""
    callbacks = {}
    for used in (program.fragment if stage is None else stage).samplers:
        binding = program.texture(used.index)
        if binding is None or binding.texture is None or binding.texture not in textures:
            continue
        texture = textures[binding.texture]
        levels = [np.asarray(level, np.float32) for level in texture.levels]
        if binding.srgb_texture:
            levels = [_srgb_levels(level) for level in levels]
        callbacks[used.index] = _make_callback(texture.kind, levels, sampler_settings(binding))
    return callbacks


def _srgb_levels(level: np.ndarray) -> np.ndarray:
    out = level.copy()
    out[..., :3] = output.srgb_to_linear(np.clip(level[..., :3], 0, 1))
    return out


def _make_callback(texture_kind: str, levels: list[np.ndarray], settings: SamplerSettings):
    def callback(coord: np.ndarray, *, kind: str | None = None, bias=None, lod=None, grad=None,
                 rows=None):
        # `kind` is what the program declared; PassProgram checks it against the binding, and
        # the texture itself decides how it is addressed. Explicit gradients (texldd) give
        # the LOD per row, as the quad differences would. `rows`: the texels of those rows
        # only (the evaluator's kept rows).
        if grad is not None:
            lod = gradient_lod(texture_kind, levels, *grad, coord=coord)
        return sample(texture_kind, levels, coord, settings, bias, lod, rows)
    return callback


_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3     # glibc mallopt parameters (malloc.h)
_malloc_tuned = False


def keep_heap_memory() -> None:
    """Ask glibc to keep freed memory for reuse instead of unmapping it. A frame allocates
    hundreds of multi-megabyte temporaries; unmapping and re-faulting them page by page costs
    more than the arithmetic (measured: a third of the rasteriser's time). Process-wide, so
    done once, and only where glibc is the allocator."""
    global _malloc_tuned
    if _malloc_tuned or not sys.platform.startswith("linux"):
        return
    _malloc_tuned = True
    try:
        libc = ctypes.CDLL("libc.so.6")
        libc.mallopt(_M_MMAP_THRESHOLD, 32 << 20)
        libc.mallopt(_M_TRIM_THRESHOLD, 512 << 20)
    except (OSError, AttributeError):
        pass


PHONG_MODES = ("taylor", "normalised")


class ReferenceBackend:
    """The NumPy renderer. `threads`: fragment shading workers (1 shades inline);
    `tune_malloc`: call `keep_heap_memory` (faster frames, memory is kept for reuse);
    `phong`: how a ShadeMode = Phong pass with `PassProgram.lighting` is lit, 'taylor'
    (Bishop and Weimer's series) or 'normalised' (the fragment program's exact lighting, as
    GL draws it; benchmarks/bench_fast_phong.py --renderer compares the two)."""

    name = "numpy"

    def __init__(self, threads: int = 2, tune_malloc: bool = True, phong: str = "taylor") -> None:
        if phong not in PHONG_MODES:
            raise ValueError(f"phong must be one of {PHONG_MODES}, got {phong!r}")
        self.phong = phong
        self.threads = max(1, int(threads))
        if tune_malloc:
            keep_heap_memory()
        self._pool: ThreadPoolExecutor | None = None
        self.framebuffer: output.Framebuffer | None = None
        # The last frame's buffers, cleared and drawn into again by a frame of the same size
        # and format (end_frame hands out a copy, so nothing else holds them).
        self._spare: output.Framebuffer | None = None

    # -- frame
    def begin_frame(self, size: tuple[int, int], clear_color=(0.0, 0.0, 0.0, 0.0),
                    clear_depth: float = 1.0, clear_stencil: int = 0, *,
                    format: str = "A8R8G8B8") -> None:
        size = tuple(int(v) for v in size)
        spare, self._spare = self._spare, None
        if spare is not None and spare.size == size and spare.format == format:
            spare.clear(clear_color, clear_depth, clear_stencil)
            self.framebuffer = spare
        else:
            self.framebuffer = output.Framebuffer.create(size, format, clear_color,
                                                         clear_depth, clear_stencil)

    def reset_shared_state(self) -> None:
        """Nothing to undo: the reference back end shares no device context."""

    def end_frame(self) -> np.ndarray:
        fb = self._target()
        self.framebuffer = None
        image = fb.image()
        self._spare = fb
        return image

    def _target(self) -> output.Framebuffer:
        if self.framebuffer is None:
            raise DrawError("no frame: call begin_frame first")
        return self.framebuffer

    # -- drawing
    def draw(self, program: PassProgram, streams: Mapping[str, np.ndarray], indices: np.ndarray,
             primitive: str, textures: Mapping[str, object]) -> None:
        fb = self._target()
        state = program.render_state
        tris = triangle_list(indices, primitive)
        uniforms = program.uniform_values()
        count = _vertex_count(streams)
        if len(tris) and (tris.min() < 0 or tris.max() >= count):
            raise DrawError(f"indices out of range for {count} vertices")
        vertex_samplers = (sampler_callbacks(program, textures, program.vertex)
                           if program.vertex is not None and program.vertex.samplers else {})
        clip, varyings = _vertex_stage(program.vertex, streams, uniforms, count, vertex_samplers)
        stage = _FragmentStage(program, clip, _needed_varyings(program.fragment, varyings),
                               uniforms, sampler_callbacks(program, textures), fb.size,
                               varyings, taylor=self.phong == "taylor")
        setup = stage.setup(tris)
        if setup is None:
            return
        # Bands of pixel rows: each is rasterised, shaded and merged on its own (a band's
        # fragments hold only its rows, so memory stays bounded by the band, not the frame),
        # and bands touch disjoint pixels, so they run in parallel and merge without order.
        bands = band_rows(fb.size, self.threads)

        def one(rows: tuple[int, int]) -> None:
            result = stage.run(setup.rows(*rows))
            if result is not None:
                output.merge(fb, state, *result)

        if self.threads > 1 and len(bands) > 1:
            list(self._executor().map(one, bands))
        else:
            for rows in bands:
                one(rows)

    def _executor(self) -> ThreadPoolExecutor:
        if self._pool is None:
            self._pool = ThreadPoolExecutor(self.threads)
        return self._pool

    def close(self) -> None:
        if self._pool is not None:
            self._pool.shutdown()
            self._pool = None


class _FragmentStage:
    """Rasterisation and the fragment program for the triangles of one draw; `run` returns
    what the output merger needs."""

    def __init__(self, program: PassProgram, clip: np.ndarray, needed: dict, uniforms: dict,
                 callbacks: dict, size: tuple[int, int],
                 varyings: dict[str, np.ndarray] | None = None, taylor: bool = True) -> None:
        self.program = program
        self.varyings = varyings if varyings is not None else needed
        self.clip = clip
        self.state = program.render_state
        self.needed = needed
        self.uniforms = uniforms
        self.callbacks = callbacks
        self.size = size
        # Helper pixels are shaded only when an op needs quad derivatives (its row says).
        self.quads = any(OPS[instr.op].needs_quads for instr in program.fragment.instrs)
        lighting = program.lighting
        self.lighting = lighting if taylor and self.state.shade_mode == "PHONG" else None
        self.taylor: taylor_lighting.TaylorLighting | None = None

    def setup(self, tris: np.ndarray) -> TriangleSetup | None:
        """The draw's triangles ready for rasterising bands of rows, or None (nothing left)."""
        state = self.state
        flat = _COLOR_VARYINGS if state.shade_mode == "FLAT" else ()
        needed, vertex_only = self.needed, ()
        if self.lighting is not None:
            # the Taylor form reads the normal and position at the vertices only; the fragment
            # program still interpolates what else reads them
            lighting = self.lighting
            given = frozenset(v for v in (lighting.diffuse_value, lighting.specular_value)
                              if v is not None)
            per_pixel = _needed_varyings(self.program.fragment, self.varyings, given)
            vertex_only = tuple(n for n in (lighting.normal, lighting.position)
                                if n in self.varyings and n not in per_pixel)
            needed = {**per_pixel, **{n: self.varyings[n][:, :3] for n in vertex_only}}
        setup = setup_triangles(self.clip, needed, tris, self.size, state.cull_mode,
                                flat=flat, depth_bias=state.depth_bias,
                                slope_scale_depth_bias=state.slope_scale_depth_bias,
                                quads=self.quads, vertex_only=vertex_only)
        if not isinstance(setup, TriangleSetup):
            return None
        if self.lighting is not None:
            self.taylor = self._taylor(setup)
        return setup

    def _taylor(self, setup: TriangleSetup) -> taylor_lighting.TaylorLighting:
        """The Taylor series of the kept triangles, from their clipped vertices' normal and
        (for a local viewer) position varyings."""
        lighting = self.lighting
        columns, col = {}, 0
        for name in setup.names:
            columns[name] = slice(col, col + setup.dims[name])
            col += setup.dims[name]
        wanted = (lighting.normal, lighting.position) if lighting.local_viewer else (lighting.normal,)
        if any(setup.dims.get(v, 0) < 3 for v in wanted):
            raise DrawError(f"PassProgram.lighting reads the varyings {wanted}, xyz; the fragment "
                            f"program interpolates {setup.dims}")
        corners = setup.attrs[setup.tris].astype(np.float64)           # (T, 3, K)
        normal = corners[..., columns[lighting.normal]][..., :3]
        position = (corners[..., columns[lighting.position]][..., :3] if lighting.local_viewer
                    else None)
        xy = np.stack([setup.X, setup.Y], axis=-1) / float(1 << SUBPIXEL_BITS)
        return taylor_lighting.prepare(lighting, xy, setup.inv_w[setup.tris], normal, position)

    def run(self, frags: QuadFragments):
        """(pixels, colour, depth, front, colour2) of the covered, unkilled fragments of
        `frags` in draw order, or None."""
        if frags.count == 0:
            return None
        keep = None if frags.covered.all() else np.nonzero(frags.covered)[0]
        colour, colour2, depth_out, killed = self._shade(frags, keep)
        if killed is not None and killed.any():
            alive = np.nonzero(~killed)[0]
            if len(alive) == 0:
                return None
            colour = colour[alive]
            colour2 = None if colour2 is None else colour2[alive]
            depth_out = None if depth_out is None else depth_out[alive]
            keep = alive if keep is None else keep[alive]
        rows = slice(None) if keep is None else keep
        depth = frags.depth[rows] if depth_out is None else np.clip(depth_out, 0, 1)
        pixels = frags.y[rows].astype(np.int64) * self.size[0] + frags.x[rows]
        return pixels, colour, depth, frags.front[rows], colour2

    def _shade(self, frags: QuadFragments, keep: np.ndarray | None):
        """Run the fragment program over the rows in chunks of whole quads, for the rows
        `keep` (every row when None: helper pixels run only what derivatives read). Returns
        colour0, colour1 or None, the depth output or None, killed or None, of those rows."""
        fragment = self.program.fragment
        chunks = [(s, min(s + _CHUNK_ROWS, frags.count))
                  for s in range(0, frags.count, _CHUNK_ROWS)]

        def run(bounds):
            start, stop = bounds
            inputs = _fragment_inputs(fragment, frags, start, stop, self.uniforms)
            kept = None
            if keep is not None:
                lo, hi = np.searchsorted(keep, (start, stop))
                kept = keep[lo:hi] - start
            return evaluate(fragment, inputs, self.callbacks, count=stop - start,
                            quads=self.quads, given=self._given(frags, start, stop), keep=kept)

        results = [run(c) for c in chunks]
        outputs = fragment.output_map
        count = frags.count if keep is None else len(keep)

        def gather(name):
            if name not in outputs:
                return None
            parts = [r.outputs[name] for r in results]
            return parts[0] if len(parts) == 1 else np.concatenate(parts)

        colour = gather("color0")
        if colour is None:
            colour = np.zeros((count, 4), np.float32)
        depth = gather("depth")
        # one program: every chunk has a kill mask (it may discard) or none has
        killed = (None if results[0].killed is None
                  else np.concatenate([r.killed for r in results]))
        return colour, gather("color1"), None if depth is None else depth[:, 0], killed

    def _given(self, frags: QuadFragments, start: int, stop: int) -> dict | None:
        """The Taylor form's lit values for rows [start, stop), by value number."""
        if self.taylor is None:
            return None
        rows = slice(start, stop)
        diffuse, specular = taylor_lighting.shade(
            self.taylor, frags.tri[rows], frags.x[rows].astype(np.float64),
            frags.y[rows].astype(np.float64))
        values = {self.lighting.diffuse_value: diffuse, self.lighting.specular_value: specular}
        return {k: v for k, v in values.items() if k is not None}


def _vertex_count(streams: Mapping[str, np.ndarray]) -> int:
    if "position" not in streams:
        raise DrawError("streams need a 'position'")
    counts = {name: len(np.asarray(v)) for name, v in streams.items() if np.ndim(v) == 2}
    if len(set(counts.values())) > 1:
        raise DrawError(f"streams disagree on the vertex count: {counts}")
    return counts["position"]


def _vertex_stage(vertex: Program | None, streams: Mapping[str, np.ndarray], uniforms: dict,
                  count: int, samplers: Mapping | None = None
                  ) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """Clip-space positions (N, 4) and the varyings (name -> (N, k) float32). `samplers`: the
    vertex program's texture lookups (vs_3_0 texldl), each at the LOD the program names."""
    if vertex is None:
        outputs = {name: np.asarray(v, np.float32) for name, v in streams.items()}
    else:
        inputs: dict[str, np.ndarray] = {}
        for item in vertex.inputs:
            if item.kind == "uniform":
                inputs[item.name] = uniforms.get(item.name, np.zeros(4, np.float32))
            elif item.name in streams:
                inputs[item.name] = streams[item.name]
            else:
                inputs[item.name] = _DEFAULTS.get(item.name, _DEFAULT_VALUE)
        outputs = evaluate(vertex, inputs, samplers or {}, count=count).outputs
        if "position" not in outputs:
            raise DrawError("the vertex program writes no position")
    position = np.asarray(outputs["position"], np.float64)
    if position.ndim != 2 or not 2 <= position.shape[1] <= 4:
        raise DrawError(f"positions must be (N, 2..4), got {position.shape}")
    if position.shape[1] < 4:
        full = np.zeros((len(position), 4))
        full[:, 3] = 1
        full[:, :position.shape[1]] = position
        position = full
    varyings = {}
    for name, value in outputs.items():
        if name in ("position", "psize"):
            continue
        value = np.asarray(value, np.float32)
        if value.ndim == 1:
            value = value[:, None]
        if name in _COLOR_VARYINGS and (vertex is None or vertex.clamp_colors):
            value = np.clip(value, 0, 1)     # below SM3 (Program.clamp_colors)
        varyings[name] = value
    return position, varyings


_COORDINATES = {"1d": 1, "2d": 2, "3d": 3, "cube": 3}


def _sampler_reads(instr) -> frozenset:
    """The coordinate components `sample` reads for this back end's samplers: the texture
    kind's coordinates, and w where it projects, biases or sets the LOD."""
    attrs = instr.attr_map
    reads = set(range(_COORDINATES[attrs["kind"]]))
    if attrs.get("proj") or attrs.get("bias") or attrs.get("lod"):
        reads.add(3)
    return frozenset(reads)


def _needed_varyings(fragment: Program, varyings: dict[str, np.ndarray],
                     given: frozenset = frozenset()) -> dict[str, np.ndarray]:
    """The varyings to interpolate: those the fragment program reads (apart from what only
    the `given` values read), cut after the last component it reads (the rest would read as
    defaults, never used)."""
    found = _NEEDED.get((id(fragment), given))
    if found is None or found[0] is not fragment:
        reads = input_components(fragment, _sampler_reads, given)
        unread = -1 if given else 0      # with given values, a varying only they read is not
        needed = {i.name: max(reads.get(i.name, ()), default=unread) + 1
                  for i in fragment.inputs if i.kind == "varying"}
        found = (fragment, sorted((n, k) for n, k in needed.items() if k > 0))
        if len(_NEEDED) > 1024:
            _NEEDED.clear()
        _NEEDED[(id(fragment), given)] = found
    return {n: varyings[n][:, :k] for n, k in found[1] if n in varyings}


# (id(fragment program), given) -> (the program, [(varying, components read)]): what a
# program reads depends on the program alone, so it is worked out once per program object
_NEEDED: dict[tuple, tuple[Program, list]] = {}


def _fragment_inputs(fragment: Program, frags: QuadFragments, start: int, stop: int,
                     uniforms: dict) -> dict[str, np.ndarray]:
    rows = slice(start, stop)
    inputs: dict[str, np.ndarray] = {}
    for item in fragment.inputs:
        if item.kind == "uniform":
            inputs[item.name] = uniforms.get(item.name, np.zeros(4, np.float32))
        elif item.kind == "builtin":
            inputs[item.name] = _builtin(item.name, frags, start, stop)
        elif item.name in frags.varyings:
            inputs[item.name] = frags.varyings[item.name][rows]
        else:
            inputs[item.name] = _DEFAULTS.get(item.name, _DEFAULT_VALUE)
    return inputs


def _builtin(name: str, frags: QuadFragments, start: int, stop: int) -> np.ndarray:
    if name == "vpos":
        out = np.zeros((stop - start, 4), np.float32)
        out[:, 0] = frags.x[start:stop]
        out[:, 1] = frags.y[start:stop]
        out[:, 3] = 1
        return out
    if name == "vface":
        sign = np.where(frags.front[start:stop], 1.0, -1.0).astype(np.float32)
        return np.repeat(sign[:, None], 4, axis=1)
    raise DrawError(f"unknown fragment builtin {name!r} (known: vpos, vface)")


register_backend("numpy", ReferenceBackend)
register_backend("reference", ReferenceBackend)
