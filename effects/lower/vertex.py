"""The fixed-function vertex pipeline (transform, D3D lighting, texgen, texture transforms,
vertex fog) lowered to vertex IR.

Conventions
- D3D row vectors: clip = pos . World . View . Projection. The lowering works in camera (eye)
  space, as Wine does: eye = pos . WorldView, clip = eye . Projection.
- Matrices are uniforms holding one *column* each, so a row vector times the matrix is one
  dp4 per component: `world_view_c0..3` (World[0] . View), `projection_c0..3`,
  `normal_c0..2` (columns of the inverse transpose of WorldView's 3x3, for normals) and
  `texture<n>_c0..3` (TextureTransform[n]).
- Inputs are named by declaration usage: position, normal, color0, color1, texcoord0..7.
  Outputs: position, color0 / color1 (saturated), texcoord<n> = the coordinates of stage n
  (the fragment side reads stage n's coordinates from there), fog.

Lighting follows the D3D9 docs ("Mathematics of Lighting", "Light Types", "Attenuation and
Spotlight Factor", "Camera-Relative Specular Lighting"), with the details that the docs leave
open taken from Wine's FFP vertex shader (test-validated): N.L is saturated; a light beyond its
Range contributes nothing (ambient included); the spotlight factor multiplies the light's
ambient too; the non-local viewer looks down +z so the eye direction is (0, 0, -1); specular
needs N.L > 0 and N.H > 0; with SpecularEnable FALSE the vertex specular passes through;
diffuse alpha is the diffuse source's alpha.
- Light uniforms (camera space, computed on the CPU): light<i>_diffuse, _specular, _ambient,
  _position (xyz), _direction (xyz, normalised; for a directional light the vector *to* the
  light), _attenuation (att0, att1, att2, range), _spot (falloff, cos(theta/2), cos(phi/2), 0).
- Material uniforms: material_diffuse, material_ambient, material_specular, material_emissive,
  material_power (x); `ambient` is the Ambient render state.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from effects.program.ir import Builder
from effects.lower.stages import FogSetup, fog_factor
from effects.program.passprogram import DirectionalLight, PixelLighting
from effects.d3d9.stage_ops import TTFF_COUNT_MASK

Vec4 = tuple[float, float, float, float]
Value = int



@dataclass(frozen=True)
class LightSetup:
    index: int
    type: str                    # POINT | SPOT | DIRECTIONAL
    diffuse: Vec4
    specular: Vec4
    ambient: Vec4
    position: tuple[float, float, float]     # world space
    direction: tuple[float, float, float]    # world space
    range: float
    attenuation: tuple[float, float, float]
    falloff: float
    theta: float
    phi: float


@dataclass(frozen=True)
class TexCoordSetup:
    """Stage `stage`'s coordinates: vertex set `set_index` or texgen `texgen`, then the
    texture transform when `transform_flags` has a count."""

    stage: int
    set_index: int = 0
    texgen: str = "PASSTHRU"
    transform_flags: int = 0
    matrix: np.ndarray = field(default_factory=lambda: np.eye(4, dtype=np.float32))


@dataclass(frozen=True)
class VertexSetup:
    """The fixed-function vertex state of a pass, resolved. Colours are (r, g, b, a)."""

    world: np.ndarray = field(default_factory=lambda: np.eye(4, dtype=np.float32))
    view: np.ndarray = field(default_factory=lambda: np.eye(4, dtype=np.float32))
    projection: np.ndarray = field(default_factory=lambda: np.eye(4, dtype=np.float32))
    lighting: bool = True
    lights: tuple[LightSetup, ...] = ()
    material_diffuse: Vec4 = (0.0, 0.0, 0.0, 0.0)
    material_ambient: Vec4 = (0.0, 0.0, 0.0, 0.0)
    material_specular: Vec4 = (0.0, 0.0, 0.0, 0.0)
    material_emissive: Vec4 = (0.0, 0.0, 0.0, 0.0)
    material_power: float = 0.0
    ambient: Vec4 = (0.0, 0.0, 0.0, 0.0)
    color_vertex: bool = True
    diffuse_source: str = "COLOR1"
    specular_source: str = "COLOR2"
    ambient_source: str = "MATERIAL"
    emissive_source: str = "MATERIAL"
    specular_enable: bool = False
    local_viewer: bool = True
    normalize_normals: bool = False
    per_pixel_lighting: bool = False     # ShadeMode = Phong: lighting moves to the fragment
    texcoords: tuple[TexCoordSetup, ...] = ()
    fog: FogSetup = FogSetup()

    @property
    def world_view(self) -> np.ndarray:
        return np.asarray(self.world, np.float64) @ np.asarray(self.view, np.float64)

    @property
    def orthographic(self) -> bool:
        """An affine projection (last column 0, 0, 0, 1): fog then uses z, not the eye depth
        (Wine's ortho_fog)."""
        p = np.asarray(self.projection, np.float64)
        return bool(np.allclose(p[:, 3], (0.0, 0.0, 0.0, 1.0)))


def _vec4(v) -> Vec4:
    a = [float(x) for x in np.ravel(v)][:4]
    a += [0.0, 0.0, 0.0, 1.0][len(a):]
    return (a[0], a[1], a[2], a[3])


class _VertexLowering:
    def __init__(self, setup: VertexSetup, uniforms: dict[str, tuple[float, ...]],
                 builder: Builder | None = None) -> None:
        self.s = setup
        self.u = uniforms
        self.b = builder or Builder("vertex")
        self._normal: Value | None = None

    def uniform(self, name: str, value, semantic: str = "") -> Value:
        self.u[name] = _vec4(value)
        return self.b.uniform(name, semantic)

    def matrix(self, name: str, m: np.ndarray, rows: int = 4) -> list[Value]:
        """Uniforms `<name>_c<j>` holding the columns of m (row-vector convention)."""
        m = np.asarray(m, np.float64).reshape(4, 4) if rows == 4 else np.asarray(m, np.float64)
        return [self.uniform(f"{name}_c{j}", m[:, j]) for j in range(m.shape[1])]

    def transform(self, v: Value, columns: list[Value], dot=None) -> Value:
        dot = dot or self.b.dp4
        parts = [dot(v, c) for c in columns]
        out = parts[0]
        for j, part in enumerate(parts[1:], start=1):
            out = self.b.merge(out, part, "xyzw"[j])
        if len(parts) == 3:
            out = self.b.merge(out, self.b.const(1.0), "w")
        return out

    def const(self, *xs: float) -> Value:
        return self.b.const(xs if len(xs) == 4 else xs[0])

    # -- geometry
    def run(self) -> None:
        b, s = self.b, self.s
        position = b.varying("position", "POSITION")
        self.eye = self.transform(position, self.matrix("world_view", s.world_view))
        self.clip = self.transform(self.eye, self.matrix("projection", s.projection))
        b.output("position", self.clip)
        if s.per_pixel_lighting and s.lighting:
            # Phong: the fragment program lights (`lower_pixel_lighting`) from the camera-space
            # position and normal interpolated here; the vertex colours pass through for the
            # material sources
            b.output("color0", b.saturate(b.varying("color0", "COLOR0")))
            b.output("color1", b.saturate(b.varying("color1", "COLOR1")))
            b.output(PHONG_EYE, self.eye)
            b.output(PHONG_NORMAL, self.normal())
        else:
            diffuse, specular = self.colors()
            b.output("color0", b.saturate(diffuse))
            b.output("color1", b.saturate(specular))
        for tc in s.texcoords:
            b.output(f"texcoord{tc.stage}", self.texcoord(tc))
        fog = self.fog()
        if fog is not None:
            b.output("fog", fog)

    def normal(self) -> Value:
        if self._normal is None:
            wv3 = self.s.world_view[:3, :3]
            try:
                normal_matrix = np.linalg.inv(wv3).T
            except np.linalg.LinAlgError:
                normal_matrix = np.zeros((3, 3))
            n_in = self.b.varying("normal", "NORMAL", components=3)
            cols = [self.uniform(f"normal_c{j}", (*normal_matrix[:, j], 0.0)) for j in range(3)]
            n = self.transform(n_in, cols, dot=self.b.dp3)
            n = self.b.merge(n, self.const(0.0), "w")
            if self.s.normalize_normals:
                n = self.b.nrm(n)
            self._normal = n
        return self._normal

    # -- colours
    def source(self, which: str, material: Vec4, src: str) -> Value:
        """A material colour or, with ColorVertex, the vertex colour it names."""
        if self.s.color_vertex and src == "COLOR1":
            return self.b.varying("color0", "COLOR0")
        if self.s.color_vertex and src == "COLOR2":
            return self.b.varying("color1", "COLOR1")
        return self.uniform(f"material_{which}", material, f"MATERIAL{which.upper()}")

    def colors(self) -> tuple[Value, Value]:
        b, s = self.b, self.s
        if not s.lighting:
            return b.varying("color0", "COLOR0"), b.varying("color1", "COLOR1")
        ambient = self.uniform("ambient", s.ambient, "AMBIENT")
        diffuse = specular = None
        for light in s.lights:
            la, ld, ls = self.light_terms(light)
            ambient = b.add(ambient, la)
            diffuse = ld if diffuse is None else b.add(diffuse, ld)
            if ls is not None:
                specular = ls if specular is None else b.add(specular, ls)
        zero = self.const(0.0)
        cd = self.source("diffuse", s.material_diffuse, s.diffuse_source)
        ca = self.source("ambient", s.material_ambient, s.ambient_source)
        ce = self.source("emissive", s.material_emissive, s.emissive_source)
        rgb = b.mad(ca, ambient, b.mad(cd, diffuse if diffuse is not None else zero, ce))
        out_diffuse = b.merge(rgb, cd, "w")
        if s.specular_enable:
            cs = self.source("specular", s.material_specular, s.specular_source)
            out_specular = b.mul(cs, specular if specular is not None else zero)
        else:
            out_specular = b.varying("color1", "COLOR1")
        return out_diffuse, out_specular

    def light_terms(self, light: LightSetup) -> tuple[Value, Value, Value | None]:
        """(ambient, diffuse, specular) contributions of one light, attenuation and spot
        factor applied."""
        b, s = self.b, self.s
        name = f"light{light.index}"
        view = np.asarray(s.view, np.float64)
        zero, one = self.const(0.0), self.const(1.0)
        if light.type == "DIRECTIONAL":
            to_light = -np.asarray(light.direction, np.float64) @ view[:3, :3]
            ldir = self.uniform(f"{name}_direction", (*_unit(to_light), 0.0))
            att = one
        else:
            pos_eye = np.append(np.asarray(light.position, np.float64), 1.0) @ view
            lpos = self.uniform(f"{name}_position", (*pos_eye[:3], 1.0))
            params = self.uniform(f"{name}_attenuation", (*light.attenuation, light.range))
            v = b.merge(b.sub(lpos, self.eye), zero, "w")
            d2 = b.dp3(v, v)
            inv_d = b.rsq(d2)
            d = b.mul(d2, inv_d)
            ldir = b.mul(v, inv_d)
            # 1 / (att0 + att1 d + att2 d^2), and nothing beyond Range
            dists = b.merge(b.merge(one, d, "y"), d2, "z")
            att = b.rcp(b.dp3(dists, params))
            att = b.cmp(b.sub(b.swizzle(params, "wwww"), d), att, zero)
            if light.type == "SPOT":
                att = b.mul(att, self.spot_factor(light, name, ldir))
        la = b.mul(self.uniform(f"{name}_ambient", light.ambient), att)
        n = self.normal()
        n_dot_l = b.dp3(n, ldir)
        ld = b.mul(b.mul(b.saturate(n_dot_l), self.uniform(f"{name}_diffuse", light.diffuse)), att)
        ld = b.merge(ld, zero, "w")
        ls = None
        if s.specular_enable:
            if s.local_viewer:
                to_eye = b.nrm(b.merge(b.neg(self.eye), zero, "w"))
            else:
                to_eye = self.const(0.0, 0.0, -1.0, 0.0)
            half = b.nrm(b.merge(b.add(ldir, to_eye), zero, "w"))
            n_dot_h = b.dp3(n, half)
            power = b.swizzle(self.uniform("material_power", (s.material_power, 0, 0, 0)), "xxxx")
            lit = b.mul(b.slt(zero, n_dot_l), b.slt(zero, n_dot_h))
            term = b.mul(b.pow(n_dot_h, power), lit)
            ls = b.mul(b.mul(term, self.uniform(f"{name}_specular", light.specular)), att)
        return la, ld, ls

    def spot_factor(self, light: LightSetup, name: str, ldir: Value) -> Value:
        """1 inside theta/2, 0 outside phi/2, ((rho - cos phi/2) / (cos theta/2 - cos phi/2))
        ^ falloff between; rho = the cosine between the spot axis and light-to-vertex."""
        b = self.b
        axis = _unit(np.asarray(light.direction, np.float64) @ np.asarray(self.s.view)[:3, :3])
        spot_dir = self.uniform(f"{name}_spotdir", (*axis, 0.0))
        cos_theta, cos_phi = np.cos(light.theta / 2), np.cos(light.phi / 2)
        params = self.uniform(f"{name}_spot", (light.falloff, cos_theta, cos_phi, 0.0))
        rho = b.dp3(b.neg(ldir), spot_dir)
        ct, cp = b.swizzle(params, "yyyy"), b.swizzle(params, "zzzz")
        t = b.saturate(b.mul(b.sub(rho, cp), b.rcp(b.sub(ct, cp))))
        partial = b.pow(t, b.swizzle(params, "xxxx"))
        zero, one = self.const(0.0), self.const(1.0)
        outside_penumbra = b.cmp(b.sub(cp, rho), zero, partial)    # rho <= cos(phi/2) -> 0
        return b.cmp(b.sub(ct, rho), outside_penumbra, one)        # rho > cos(theta/2) -> 1

    # -- texture coordinates
    def reflection(self) -> Value:
        """reflect(normalize(eye), N) = I - 2 (N . I) N (Wine's texgen)."""
        b = self.b
        i = b.nrm(b.merge(self.eye, self.const(0.0), "w"))
        n = self.normal()
        r = b.sub(i, b.mul(b.mul(b.dp3(n, i), self.const(2.0)), n))
        return b.merge(r, self.const(1.0), "w")

    def texcoord(self, tc: TexCoordSetup) -> Value:
        b = self.b
        one = self.const(1.0)
        if tc.texgen == "CAMERASPACENORMAL":
            coord = b.merge(self.normal(), one, "w")
        elif tc.texgen == "CAMERASPACEPOSITION":
            coord = b.merge(self.eye, one, "w")
        elif tc.texgen == "CAMERASPACEREFLECTIONVECTOR":
            coord = self.reflection()
        elif tc.texgen == "SPHEREMAP":
            r = self.reflection()
            # m = 2 sqrt(rx^2 + ry^2 + (rz + 1)^2); (rx / m + 1/2, ry / m + 1/2, 0, 1)
            shifted = b.add(b.merge(r, self.const(0.0), "w"), self.const(0.0, 0.0, 1.0, 0.0))
            inv_m = b.mul(b.rsq(b.dp3(shifted, shifted)), self.const(0.5))
            uv = b.mad(r, inv_m, self.const(0.5))
            coord = b.merge(self.const(0.0, 0.0, 0.0, 1.0), uv, "xy")
        else:
            coord = b.varying(f"texcoord{tc.set_index}", f"TEXCOORD{tc.set_index}")
        if tc.transform_flags & TTFF_COUNT_MASK:
            coord = self.transform(coord, self.matrix(f"texture{tc.stage}", tc.matrix))
        return coord

    # -- fog
    def fog(self) -> Value | None:
        b, fog = self.b, self.s.fog
        if fog.source not in ("vertex", "table"):
            return None
        if fog.source == "vertex" and fog.range_fog:
            distance = b.mul(b.dp3(self.eye, self.eye), b.rsq(b.dp3(self.eye, self.eye)))
        elif self.s.orthographic:
            distance = b.swizzle(self.clip, "zzzz")
        else:
            distance = b.abs(b.swizzle(self.eye, "zzzz"))
        if fog.source == "table":
            return distance
        self.u["fog_params"] = fog.params
        return fog_factor(b, distance, fog.vertex_mode, b.uniform("fog_params", "FOG"))


# The varyings of per-pixel (ShadeMode = Phong) lighting: camera-space position and normal, in
# the last two texture-coordinate interpolators (a Phong pass may use stages 0-5).
PHONG_SLOTS = (6, 7)
PHONG_EYE, PHONG_NORMAL = (f"texcoord{n}" for n in PHONG_SLOTS)


class _PixelLighting(_VertexLowering):
    """The vertex lighting equations evaluated in the fragment program, per pixel, from the
    interpolated camera-space position and the interpolated normal normalised at each pixel:
    Phong shading, which Direct3D named (D3DSHADE_PHONG) and no device built."""

    def __init__(self, setup: VertexSetup, uniforms: dict[str, tuple[float, ...]],
                 builder: Builder) -> None:
        super().__init__(setup, uniforms, builder)
        self.eye = builder.varying(PHONG_EYE, PHONG_EYE.upper())

    def normal(self) -> Value:
        if self._normal is None:
            n = self.b.varying(PHONG_NORMAL, PHONG_NORMAL.upper())
            self._normal = self.b.nrm(self.b.merge(n, self.const(0.0), "w"))
        return self._normal


def lower_pixel_lighting(setup: VertexSetup, uniforms: dict[str, tuple[float, ...]],
                         builder: Builder) -> tuple[Value, Value]:
    """(diffuse, specular) of the fixed-function lighting, per pixel, in `builder` (a fragment
    program); saturated as the vertex colours are."""
    lighting = _PixelLighting(setup, uniforms, builder)
    diffuse, specular = lighting.colors()
    return builder.saturate(diffuse), builder.saturate(specular)


def pixel_lighting(setup: VertexSetup, diffuse_value: int | None,
                   specular_value: int | None) -> PixelLighting | None:
    """The per-pixel lighting of `setup` as data (`PixelLighting`), naming the fragment
    program's lit values; None where the model is not the one the data describes: a light
    that is not directional (L varies over the triangle) or a material colour read from the
    vertex colours (ColorVertex with a COLOR1/COLOR2 source)."""
    s = setup
    if not s.specular_enable:
        specular_value = None
    if diffuse_value is None and specular_value is None:   # the program reads neither
        return None
    if any(light.type != "DIRECTIONAL" for light in s.lights):
        return None
    sources = [s.diffuse_source, s.ambient_source, s.emissive_source]
    if s.specular_enable:
        sources.append(s.specular_source)
    if s.color_vertex and any(src in ("COLOR1", "COLOR2") for src in sources):
        return None
    view3 = np.asarray(s.view, np.float64)[:3, :3]
    ambient = np.array(s.ambient, np.float64)
    lights = []
    for light in s.lights:
        ambient = ambient + np.array(light.ambient, np.float64)   # attenuation 1
        to_light = _unit(-np.asarray(light.direction, np.float64) @ view3)
        lights.append(DirectionalLight(to_light, _vec4(light.diffuse), _vec4(light.specular)))
    base = np.array(s.material_ambient, np.float64) * ambient + np.array(s.material_emissive)
    return PixelLighting(diffuse_value, specular_value,
                         PHONG_NORMAL, PHONG_EYE, tuple(lights), _vec4(base),
                         _vec4(s.material_diffuse), _vec4(s.material_specular),
                         float(s.material_power), bool(s.local_viewer))


def _unit(v: np.ndarray) -> tuple[float, float, float]:
    n = float(np.linalg.norm(v))
    v = v / n if n > 0 else v
    return float(v[0]), float(v[1]), float(v[2])


def lower_vertex(setup: VertexSetup, uniforms: dict[str, tuple[float, ...]]):
    """The vertex Program for `setup`; the values of its uniforms are added to `uniforms`."""
    lowering = _VertexLowering(setup, uniforms)
    lowering.run()
    return lowering.b.build()
