"""NumPy reference, GL path and hand-written GLSL side by side: one 512x512 per-pixel Phong
sphere (fxfiles/phong.fx, PerPixelPhong_ps20, as a Radeon 9700 selects it) in the default
scene, in milliseconds per frame.

    .venv/bin/python benchmarks/bench_render.py [--frames N] [--size S] [--profile numpy|gl]

What each figure includes (median of N frames after warm-up frames; lowering is cached, so a
frame repeats only its cache lookup; textures and meshes are loaded once):
  reference     effects.Runtime.render on the NumPy back end: lowering lookup, clear, vertex
                program, rasterisation, fragment program, output merge, the uint8 image.
  GL path       the same Runtime.render on the GL back end (moderngl, headless EGL; llvmpipe
                on a machine without a GPU): lowering lookup, clear, uniform and texture
                binding, draw, glReadPixels into a uint8 image.
  hand-written  a GLSL 330 program written by hand for the same shading (Persson's ps.2.0
                Phong as phong.fx writes it), same mesh, textures and render state, drawn with
                moderngl directly: clear, uniforms, draw, the same read-back; with the GL back
                end's texture and target formats (the goal's measure), and "native" with the
                formats such a program would choose (8-bit textures, 24-bit depth).
The pictures are compared too (PSNR), to show that the three draw the same thing.
Goals (issue 6): GL path <= 1.2x hand-written; reference <= 13x GL path and <= 60 ms.
"""
from __future__ import annotations

import argparse
import cProfile
import math
import os
import platform
import pstats
import sys
import time
from pathlib import Path

import moderngl
import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from effects.program.backend import create_backend, triangle_list  # noqa: E402
from backends.gl.context import headless_context  # noqa: E402
from effects.d3d9.caps import load_profile  # noqa: E402
from effects.api import load_effect  # noqa: E402
from effects.host.runtime import Runtime  # noqa: E402

VERTEX_SHADER = """
#version 330 core
in vec3 position;
in vec3 normal;
in vec3 tangent;
in vec2 texcoord0;
uniform mat4 world_view_projection;   // Direct3D row-vector matrices, uploaded row by row:
uniform mat4 world;                   // GLSL sees the transpose, so M * p is D3D's p * M
uniform vec3 camera_position;
uniform vec3 light_position;
uniform vec2 pixel_size;              // (2/W, 2/H)
out vec2 uv;
out vec3 light_tangent;               // unnormalised, in tangent space
out vec3 view_tangent;

void main() {
    vec4 p = world_view_projection * vec4(position, 1.0);
    vec3 world_position = (world * vec4(position, 1.0)).xyz;
    vec3 t = mat3(world) * tangent;
    vec3 n = mat3(world) * normal;
    vec3 b = cross(n, t);
    mat3 to_tangent = transpose(mat3(t, b, n));
    light_tangent = to_tangent * (light_position - world_position);
    view_tangent = to_tangent * (camera_position - world_position);
    uv = texcoord0;
    // D3D9 pixel centres (half a pixel), row 0 at the top, depth 0..w to -w..w
    gl_Position = vec4(p.x + 0.5 * pixel_size.x * p.w, -(p.y - 0.5 * pixel_size.y * p.w),
                       2.0 * p.z - p.w, p.w);
}
"""

FRAGMENT_SHADER = """
#version 330 core
in vec2 uv;
in vec3 light_tangent;
in vec3 view_tangent;
uniform sampler2D base_map;
uniform sampler2D normal_map;
uniform sampler2D gloss_map;
uniform float specular_power;
uniform float attenuation_constant;
uniform float attenuation_quadratic;
uniform vec4 ambient;
uniform vec4 light_color;
out vec4 color;

void main() {
    vec4 base = texture(base_map, uv);
    vec4 gloss = texture(gloss_map, uv);
    vec3 n = normalize(texture(normal_map, uv).xyz * 2.0 - 1.0);
    float distance2 = dot(light_tangent, light_tangent);
    vec3 l = light_tangent * inversesqrt(distance2);
    float attenuation = 1.0 / (attenuation_quadratic * distance2 + attenuation_constant);
    float n_dot_l = dot(l, n);
    float diffuse = clamp(n_dot_l, 0.0, 1.0);
    vec3 r = 2.0 * n_dot_l * n - l;
    float specular = pow(clamp(dot(r, normalize(view_tangent)), 0.0, 1.0), specular_power);
    vec4 lit = (diffuse * base + specular * gloss) * attenuation * light_color;
    color = base * ambient + lit;
}
"""


class HandWritten:
    """The same Phong sphere drawn with moderngl directly: everything made once, a frame is
    clear + uniforms + draw + read-back.

    formats "same": the GL back end's formats, so that only the framework's own work differs:
    RGBA32F textures (the back end filters decoded texels in float to match the reference)
    and an RGBA8 + DEPTH32F_STENCIL8 target (the reference keeps float depth; effects set
    stencil states). formats "native": what a program written for this one picture would
    pick: RGBA8 textures and moderngl's default 24-bit depth buffer."""

    def __init__(self, runtime: Runtime, formats: str = "same") -> None:
        self.ctx = headless_context()
        self.formats = formats
        ctx = self.ctx
        self.size = runtime.size
        self.clear = runtime.scene.clear_color
        self.program = ctx.program(vertex_shader=VERTEX_SHADER, fragment_shader=FRAGMENT_SHADER)
        geometry = runtime.geometry()
        streams = geometry.streams
        content = [(ctx.buffer(np.ascontiguousarray(streams[name], np.float32)), fmt, name)
                   for name, fmt in (("position", "3f"), ("normal", "3f"), ("tangent", "3f"),
                                     ("texcoord0", "2f"))]
        tris = triangle_list(geometry.indices, geometry.primitive).astype(np.uint32)
        self.vao = ctx.vertex_array(self.program, content, ctx.buffer(tris.tobytes()),
                                    index_element_size=4)
        self.textures = []
        for unit, (name, uniform) in enumerate((("BaseTexture", "base_map"),
                                                ("NormalMap", "normal_map"),
                                                ("GlossMap", "gloss_map"))):
            self.textures.append((unit, self._texture(runtime.texture(name))))
            self.program[uniform].value = unit
        def value(name: str):
            return runtime.effect.parameter(name).value

        for uniform, name in (("specular_power", "SpecularPower"),
                              ("attenuation_constant", "AttenuationConstant"),
                              ("attenuation_quadratic", "AttenuationQuadratic")):
            self.program[uniform].value = float(np.ravel(value(name))[0])
        self.program["ambient"].value = tuple(float(v) for v in np.ravel(value("AmbientColor")))
        self.program["light_color"].value = tuple(float(v) for v in np.ravel(value("LightColor")))
        self.matrices = {"world_view_projection": value("WorldViewProjection"),
                         "world": value("World")}
        self.vectors = {"camera_position": np.ravel(value("CameraPosition"))[:3],
                        "light_position": np.ravel(value("LightPosition"))[:3]}
        self.fbo = (self._same_target() if formats == "same" else
                    ctx.framebuffer(ctx.texture(self.size, 4), ctx.depth_renderbuffer(self.size)))

    def _same_target(self) -> moderngl.Framebuffer:
        """RGBA8 colour and a packed float depth + stencil renderbuffer (moderngl has no
        packed depth-stencil format, so these few calls go through backends.gl.rawgl)."""
        from backends.gl import rawgl as G
        gl = G.raw_gl()
        self.colour = self.ctx.texture(self.size, 4)
        depth = gl.gen("Renderbuffers")
        gl.glBindRenderbuffer(G.RENDERBUFFER, depth)
        gl.glRenderbufferStorage(G.RENDERBUFFER, G.DEPTH32F_STENCIL8, *self.size)
        framebuffer = gl.gen("Framebuffers")
        gl.glBindFramebuffer(G.FRAMEBUFFER, framebuffer)
        gl.glFramebufferTexture2D(G.FRAMEBUFFER, G.COLOR_ATTACHMENT0, G.TEXTURE_2D,
                                  self.colour.glo, 0)
        gl.glFramebufferRenderbuffer(G.FRAMEBUFFER, G.DEPTH_STENCIL_ATTACHMENT, G.RENDERBUFFER,
                                     depth)
        assert gl.glCheckFramebufferStatus(G.FRAMEBUFFER) == G.FRAMEBUFFER_COMPLETE
        return self.ctx.detect_framebuffer(framebuffer)

    def _texture(self, texture) -> moderngl.Texture:
        """Every level of an effects Texture, trilinear filtered, repeating: as float32 RGBA
        (formats "same") or 8-bit RGBA (formats "native")."""
        levels = [np.asarray(level, np.float32) for level in texture.levels]
        height, width = levels[0].shape[:2]
        native = self.formats == "native"
        gl_texture = self.ctx.texture((width, height), 4, dtype="f1" if native else "f4")
        gl_texture.build_mipmaps(0, len(levels) - 1)
        for index, level in enumerate(levels):
            texels = np.rint(np.clip(level, 0, 1) * 255).astype(np.uint8) if native else level
            gl_texture.write(np.ascontiguousarray(texels), level=index)
        gl_texture.filter = (moderngl.LINEAR_MIPMAP_LINEAR, moderngl.LINEAR)
        gl_texture.repeat_x = gl_texture.repeat_y = True
        return gl_texture

    def frame(self) -> np.ndarray:
        ctx = self.ctx
        self.fbo.use()
        ctx.enable_only(moderngl.DEPTH_TEST | moderngl.CULL_FACE)
        ctx.depth_func = "<="
        ctx.front_face = "ccw"
        ctx.cull_face = "back"      # D3D culls counter-clockwise on screen: GL sees y flipped
        self.fbo.clear(*self.clear, depth=1.0)
        for name, matrix in self.matrices.items():
            self.program[name].write(np.ascontiguousarray(matrix, np.float32))
        for name, vector in self.vectors.items():
            self.program[name].value = tuple(float(v) for v in vector)
        self.program["pixel_size"].value = (2.0 / self.size[0], 2.0 / self.size[1])
        for unit, texture in self.textures:
            texture.use(unit)
        self.vao.render(moderngl.TRIANGLES)
        image = np.empty((self.size[1], self.size[0], 4), np.uint8)  # a new image per frame,
        self.fbo.read_into(image, components=4, alignment=1)          # as Runtime.render gives
        return image


def time_frames(frames_by_name: dict, rounds: int, warmup: int) -> dict:
    """name -> (median ms, best ms, last image): `warmup` untimed rounds, then `rounds` timed
    ones, the paths interleaved frame by frame so that a busy machine slows all alike."""
    images = {}
    for _ in range(warmup):
        for name, frame in frames_by_name.items():
            images[name] = frame()
    times = {name: [] for name in frames_by_name}
    for _ in range(rounds):
        for name, frame in frames_by_name.items():
            start = time.perf_counter()
            images[name] = frame()
            times[name].append(time.perf_counter() - start)
    return {name: (1000 * float(np.median(t)), 1000 * min(t), np.array(images[name]))
            for name, t in times.items()}


def psnr(a: np.ndarray, b: np.ndarray) -> float:
    mse = np.mean((a.astype(np.float64) - b.astype(np.float64)) ** 2)
    return math.inf if mse == 0 else 10 * math.log10(255.0 ** 2 / mse)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=40)
    parser.add_argument("--warmup", type=int, default=5)
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--card", default="radeon9700")
    parser.add_argument("--profile", choices=("numpy", "gl"),
                        help="also print a cProfile of that path")
    args = parser.parse_args()
    effect = load_effect(str(ROOT / "fxfiles" / "phong.fx"))
    profile = load_profile(args.card)
    size = (args.size, args.size)
    reference = Runtime(effect, profile, size=size, backend=create_backend("numpy"))
    gl_path = Runtime(effect, profile, size=size, backend=create_backend("gl"))
    technique = reference.select()
    hand = HandWritten(gl_path, "same")
    native = HandWritten(gl_path, "native")

    def ref_frame():
        return reference.render(technique).image

    def gl_frame():
        return gl_path.render(technique).image

    gl_results = time_frames({"hand": hand.frame, "gl": gl_frame, "native": native.frame},
                             args.frames, args.warmup)
    hand_ms, hand_best, hand_image = gl_results["hand"]
    gl_ms, gl_best, gl_image = gl_results["gl"]
    native_ms, native_best, _ = gl_results["native"]
    ref_ms, ref_best, ref_image = time_frames({"ref": ref_frame}, max(5, args.frames // 4),
                                              2)["ref"]

    renderer = headless_context().info.get("GL_RENDERER", "?")
    print(f"{args.size}x{args.size} per-pixel Phong sphere: phong.fx {technique.name} on "
          f"{profile.display_name or profile.name}")
    print(f"machine: {platform.machine()}, {os.cpu_count()} CPU cores, GL renderer {renderer}")
    print(f"{'':14s}{'median ms':>11s}{'best ms':>10s}")
    for name, median, best in (("reference", ref_ms, ref_best), ("GL path", gl_ms, gl_best),
                               ("hand-written", hand_ms, hand_best),
                               ("  (native)", native_ms, native_best)):
        print(f"{name:14s}{median:11.2f}{best:10.2f}")
    print(f"GL path / hand-written = {gl_ms / hand_ms:.2f} (goal <= 1.2; "
          f"{gl_ms / native_ms:.2f} against the native formats)")
    print(f"reference / GL path    = {ref_ms / gl_ms:.1f} (goal <= 13)")
    print(f"reference per frame    = {ref_ms:.1f} ms (goal <= 60)")
    print(f"same picture: PSNR reference-GL {psnr(ref_image, gl_image):.1f} dB, "
          f"GL-hand-written {psnr(gl_image, hand_image):.1f} dB")
    if args.profile:
        frame = ref_frame if args.profile == "numpy" else gl_frame
        path = f"/tmp/bench_render_{args.profile}.prof"
        cProfile.runctx("for _ in range(10): frame()", globals(), {"frame": frame}, path)
        pstats.Stats(path).sort_stats("tottime").print_stats(20)


if __name__ == "__main__":
    main()
