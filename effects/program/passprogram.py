"""What one lowered pass hands to a back end: programs, render state, texture bindings, uniforms.

Every field defaults to Direct3D 9's device default, so `RenderState()` is the state a fresh
device starts in (D3DRENDERSTATETYPE and D3DSAMPLERSTATETYPE documentation). Enum values are the
canonical state-value names of the effect files, without prefix (`LESSEQUAL`, `CCW`, `ONE`);
colours are (r, g, b, a) floats. Back ends map them to GL; they never see a caps profile.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping

import numpy as np

from effects.program.ir import IRError, Program

Color = tuple[float, float, float, float]


@dataclass(frozen=True)
class RenderState:
    """Raster, depth, stencil and blend state of a pass (D3D9 defaults). Fog and the
    fixed-function specular add are not here: lowering folds both into the programs
    (`effects.lower.passes`), so back ends have one implementation of each, the IR's."""

    # Depth: D3DZB_TRUE because the framework's device always has a depth buffer
    # (D3D9 defaults ZENABLE to TRUE when the device is created with an auto depth stencil).
    z_enable: bool = True
    z_write_enable: bool = True
    z_func: str = "LESSEQUAL"
    depth_bias: float = 0.0
    slope_scale_depth_bias: float = 0.0
    # Rasterisation
    cull_mode: str = "CCW"                 # NONE | CW | CCW (which winding is culled)
    fill_mode: str = "SOLID"               # POINT | WIREFRAME | SOLID
    shade_mode: str = "GOURAUD"            # FLAT | GOURAUD | PHONG (lit per pixel by the lowering)
    scissor_test_enable: bool = False
    clip_plane_enable: int = 0             # bit i enables user clip plane i
    # Alpha test: compares the 8-bit output alpha with alpha_ref (0..255)
    alpha_test_enable: bool = False
    alpha_func: str = "ALWAYS"
    alpha_ref: int = 0
    # Blending
    alpha_blend_enable: bool = False
    src_blend: str = "ONE"
    dest_blend: str = "ZERO"
    blend_op: str = "ADD"
    separate_alpha_blend_enable: bool = False
    src_blend_alpha: str = "ONE"
    dest_blend_alpha: str = "ZERO"
    blend_op_alpha: str = "ADD"
    blend_factor: Color = (1.0, 1.0, 1.0, 1.0)   # 0xFFFFFFFF
    color_write_enable: int = 0xF                # bits: 1 red, 2 green, 4 blue, 8 alpha
    dither_enable: bool = False
    srgb_write_enable: bool = False
    # Stencil
    stencil_enable: bool = False
    stencil_func: str = "ALWAYS"
    stencil_ref: int = 0
    stencil_mask: int = 0xFFFFFFFF
    stencil_write_mask: int = 0xFFFFFFFF
    stencil_fail: str = "KEEP"
    stencil_zfail: str = "KEEP"
    stencil_pass: str = "KEEP"
    two_sided_stencil_mode: bool = False
    ccw_stencil_func: str = "ALWAYS"
    ccw_stencil_fail: str = "KEEP"
    ccw_stencil_zfail: str = "KEEP"
    ccw_stencil_pass: str = "KEEP"


@dataclass(frozen=True)
class TextureBinding:
    """The texture on one sampler slot and that sampler's state (D3DSAMP_* defaults).
    `texture` names the effect parameter, or a generated texture (normalisation cube map,
    power table) by a key the lowering chooses; None leaves the slot unbound."""

    sampler: int
    texture: str | None = None
    kind: str = "2d"
    address_u: str = "WRAP"
    address_v: str = "WRAP"
    address_w: str = "WRAP"
    border_color: Color = (0.0, 0.0, 0.0, 0.0)
    mag_filter: str = "POINT"
    min_filter: str = "POINT"
    mip_filter: str = "NONE"
    mip_lod_bias: float = 0.0
    max_mip_level: int = 0
    max_anisotropy: int = 1
    srgb_texture: bool = False


@dataclass(frozen=True)
class DirectionalLight:
    """One directional light of `PixelLighting`, in camera space: the unit vector toward the
    light and its diffuse and specular colours."""

    direction: tuple[float, float, float]
    diffuse: Color
    specular: Color


@dataclass(frozen=True)
class PixelLighting:
    """The fixed-function lighting a ShadeMode = Phong pass evaluates per pixel, as data, for a
    back end that shades it its own way (the reference's Bishop-Weimer Taylor form). The
    fragment program computes the same lighting exactly (normalised interpolated normal), so a
    back end may ignore this. The lowering gives it only where every light is directional and
    every material colour comes from the material (the paper's model: L constant over a
    triangle); the values of the D3D lighting equations (`effects.lower.vertex`) become:

        diffuse  = sat(base + material_diffuse * sum_i sat(N.L_i) diffuse_i), alpha
                   material_diffuse's
        specular = sat(material_specular * sum_i [N.L_i > 0] [N.H_i > 0] (N.H_i)^power
                   specular_i)

    with N the interpolated camera-space normal (varying `normal`, xyz), H_i the half vector of
    L_i and the eye direction: (0, 0, -1) or, with `local_viewer`, toward the eye from the
    interpolated camera-space position (varying `position`). `diffuse_value` and
    `specular_value` are the numbers of the fragment program's values that hold them (None:
    the program does not read it, or SpecularEnable is off and the vertex specular passes
    through)."""

    diffuse_value: int | None
    specular_value: int | None
    normal: str
    position: str
    lights: tuple[DirectionalLight, ...]
    base: Color                  # emissive + material ambient * (Ambient + the lights' ambient)
    material_diffuse: Color
    material_specular: Color
    power: float
    local_viewer: bool


@dataclass(frozen=True)
class PassProgram:
    """One pass, lowered. `vertex` None means the positions stream is already in D3D clip
    space and every stream passes straight to the fragment program as the varying of the same
    name (what back-end tests use; lowering always produces a vertex program).
    `uniforms` is (name, vec4) pairs: constant registers, one row of a matrix each.
    `textures` binds the samplers of both programs; the vertex program's are other slots
    than the fragment program's (vs_3_0 vertex textures are samplers 257-260)."""

    fragment: Program
    vertex: Program | None = None
    render_state: RenderState = RenderState()
    textures: tuple[TextureBinding, ...] = ()
    uniforms: tuple[tuple[str, tuple[float, float, float, float]], ...] = ()
    lighting: PixelLighting | None = None

    def __post_init__(self) -> None:
        if self.fragment.stage != "fragment":
            raise IRError("PassProgram.fragment must be a fragment program")
        if self.vertex is not None and self.vertex.stage != "vertex":
            raise IRError("PassProgram.vertex must be a vertex program")
        slots = [t.sampler for t in self.textures]
        if len(set(slots)) != len(slots):
            raise IRError(f"sampler slots bound twice: {slots}")
        vertex_samplers = self.vertex.samplers if self.vertex is not None else ()
        if {s.index for s in vertex_samplers} & {s.index for s in self.fragment.samplers}:
            raise IRError("a sampler slot is sampled by both the vertex and the fragment program")
        for binding in (*self.fragment.samplers, *vertex_samplers):
            texture = self.texture(binding.index)
            if texture is not None and texture.kind != binding.kind:
                raise IRError(f"sampler {binding.index}: program samples {binding.kind}, "
                              f"texture binding is {texture.kind}")
        for name, value in self.uniforms:
            if len(value) != 4:
                raise IRError(f"uniform {name} must have 4 components")
        if self.lighting is not None:
            values = {i.dest for i in self.fragment.instrs if i.dest is not None}
            named = (self.lighting.diffuse_value, self.lighting.specular_value)
            if any(v is not None and v not in values for v in named):
                raise IRError(f"PassProgram.lighting names values {named} the fragment "
                              "program does not have")

    def texture(self, sampler: int) -> TextureBinding | None:
        for binding in self.textures:
            if binding.sampler == sampler:
                return binding
        return None

    def uniform_values(self) -> dict[str, np.ndarray]:
        """The uniforms as float32 vec4 arrays, ready for `evaluate(..., inputs=)`."""
        return {name: np.array(value, dtype=np.float32) for name, value in self.uniforms}

    @staticmethod
    def pack_uniforms(values: Mapping[str, object]) -> tuple[tuple[str, tuple[float, ...]], ...]:
        """(name, vec4) pairs from a mapping of 1- to 4-component values (missing components
        read (0, 0, 0, 1), as inputs do), sorted by name for a stable hash."""
        packed = []
        for name in sorted(values):
            v = np.ravel(np.asarray(values[name], dtype=np.float32))
            if not 1 <= v.size <= 4:
                raise IRError(f"uniform {name} must have 1 to 4 components, got {v.size}")
            full = np.array([0, 0, 0, 1], dtype=np.float32)
            full[:v.size] = v
            packed.append((name, tuple(float(x) for x in full)))
        return tuple(packed)
