"""The fixed-function vertex pipeline, lowered and run on the NumPy evaluator, against the D3D
lighting and texgen formulas worked out by hand."""
from __future__ import annotations

import math

import numpy as np
import pytest

import effects
from backends.reference.evaluate import evaluate
from effects.d3d9.caps import load_profile
from effects.lower.passes import lower_pass


def lower(states: str, params: str = ""):
    effect = effects.load_effect(f"""texture Tex0; {params}
        technique t {{ pass p {{ {states} }} }}""")
    return lower_pass(effect, effect.techniques[0], 0, load_profile("modern"))


def run_vertex(pp, position=(0, 0, 0, 1), normal=(0, 0, -1), color0=(1, 1, 1, 1),
               color1=(0, 0, 0, 0), texcoords=None):
    inputs = pp.uniform_values()
    given = {"position": position, "normal": normal, "color0": color0, "color1": color1}
    for n, tc in (texcoords or {}).items():
        given[f"texcoord{n}"] = tc
    for item in pp.vertex.inputs:
        if item.kind == "varying":
            inputs[item.name] = np.array([given.get(item.name, (0, 0, 0, 1))], np.float32)
    return {k: v[0] for k, v in evaluate(pp.vertex, inputs, count=1).outputs.items()}


def close(actual, expected, atol=1e-5):
    np.testing.assert_allclose(np.asarray(actual, np.float64), np.asarray(expected, np.float64),
                               atol=atol)


MATRICES = """
    float4x4 World = {1,0,0,0, 0,1,0,0, 0,0,1,0, 1,2,3,1};
    float4x4 View = {2,0,0,0, 0,2,0,0, 0,0,2,0, 0,0,0,1};
    float4x4 Proj = {1,0,0,0, 0,1,0,0, 0,0,0.5,1, 0,0,-1,0};"""


def test_position_is_pos_world_view_projection_in_row_vector_order():
    pp = lower("WorldTransform[0] = <World>; ViewTransform = <View>; "
               "ProjectionTransform = <Proj>; Lighting = FALSE;", MATRICES)
    out = run_vertex(pp, position=(1, 1, 1, 1))
    # world: (2, 3, 4, 1); view: (4, 6, 8, 1); proj: (4, 6, 8 * 0.5 - 1, 8)
    close(out["position"], (4, 6, 3, 8))


def test_lighting_off_passes_vertex_colours_through_saturated():
    pp = lower("Lighting = FALSE;")
    out = run_vertex(pp, color0=(1.5, 0.5, -0.25, 0.75), color1=(0.25, 0, 2, 0))
    close(out["color0"], (1, 0.5, 0, 0.75))
    close(out["color1"], (0.25, 0, 1, 0))


DIRECTIONAL = """LightEnable[0] = TRUE; LightType[0] = Directional;
    LightDirection[0] = {0, 0, 1}; LightDiffuse[0] = {1, 1, 1, 1};
    LightSpecular[0] = {1, 1, 1, 1};
    MaterialDiffuse = {1, 0.5, 0.25, 0.75}; MaterialAmbient = {1, 1, 1, 1};
    MaterialSpecular = {1, 1, 1, 1}; MaterialPower = 4.0;
    Ambient = 0x00202020; ColorVertex = FALSE;"""
N = (0, 0.6, -0.8)  # unit normal; the light shines down +z, so L = (0, 0, -1), N.L = 0.8


def test_directional_light_diffuse_plus_ambient():
    out = run_vertex(lower(DIRECTIONAL), normal=N)
    ga = 0x20 / 255
    close(out["color0"], (0.8 * 1 + ga, 0.8 * 0.5 + ga, 0.8 * 0.25 + ga, 0.75))
    close(out["color1"], (0, 0, 0, 0))  # SpecularEnable FALSE: vertex specular passes


def test_directional_light_uses_the_vertex_colour_with_colorvertex():
    pp = lower(DIRECTIONAL.replace("ColorVertex = FALSE;", "ColorVertex = TRUE;"))
    out = run_vertex(pp, normal=N, color0=(0.5, 0.5, 0.5, 0.25))
    ga = 0x20 / 255
    # DiffuseMaterialSource defaults to COLOR1 (the vertex diffuse); ambient stays material
    close(out["color0"], (0.4 + ga, 0.4 + ga, 0.4 + ga, 0.25))


def test_directional_specular_nonlocal_viewer():
    pp = lower(DIRECTIONAL + "SpecularEnable = TRUE; LocalViewer = FALSE;")
    out = run_vertex(pp, normal=N)
    # eye direction (0, 0, -1): H = norm(L + E) = (0, 0, -1); N.H = 0.8; 0.8^4
    close(out["color1"][:3], [0.8 ** 4] * 3)


def test_directional_specular_local_viewer():
    pp = lower(DIRECTIONAL + "SpecularEnable = TRUE;")
    out = run_vertex(pp, position=(3, 0, 4, 1), normal=N)
    # E = norm(-(3, 0, 4)) = (-0.6, 0, -0.8); L + E = (-0.6, 0, -1.8), |.| = sqrt(3.6)
    n_dot_h = (0.6 * 0 + (-0.8) * (-1.8)) / math.sqrt(3.6)
    close(out["color1"][:3], [n_dot_h ** 4] * 3)


def test_back_facing_light_gives_no_diffuse_or_specular():
    pp = lower(DIRECTIONAL + "SpecularEnable = TRUE; Ambient = 0;")
    out = run_vertex(pp, normal=(0, 0, 1))
    close(out["color0"][:3], (0, 0, 0))
    close(out["color1"][:3], (0, 0, 0))


POINT = """LightEnable[0] = TRUE; LightType[0] = Point; LightPosition[0] = {{0, 0, -2}};
    LightDiffuse[0] = {{0.9, 0.6, 0.3, 1}}; LightAmbient[0] = {{0.3, 0.3, 0.3, 1}};
    LightAttenuation0[0] = 0.5; LightAttenuation1[0] = 0.25; LightAttenuation2[0] = 0.125;
    LightRange[0] = {range};
    MaterialDiffuse = {{1, 1, 1, 1}}; MaterialAmbient = {{1, 1, 1, 1}}; ColorVertex = FALSE;"""


def test_point_light_with_attenuation():
    out = run_vertex(lower(POINT.format(range=10.0)), normal=(0, 0, -1))
    att = 1 / (0.5 + 0.25 * 2 + 0.125 * 4)  # d = 2: 2/3
    close(out["color0"][:3], (0.9 * att + 0.3 * att, 0.6 * att + 0.3 * att, 0.3 * att + 0.3 * att))


def test_point_light_beyond_its_range_contributes_nothing():
    out = run_vertex(lower(POINT.format(range=1.5)), normal=(0, 0, -1))
    close(out["color0"][:3], (0, 0, 0))


def test_spot_light_between_umbra_and_penumbra():
    pp = lower("""LightEnable[0] = TRUE; LightType[0] = Spot; LightPosition[0] = {0, 0, -2};
        LightDirection[0] = {0, 0, 1}; LightDiffuse[0] = {1, 1, 1, 1}; LightRange[0] = 100;
        LightAttenuation0[0] = 1; LightTheta[0] = 0.5; LightPhi[0] = 1.0; LightFalloff[0] = 1;
        MaterialDiffuse = {1, 1, 1, 1}; ColorVertex = FALSE;""")
    x = 2 * math.tan(0.4)  # the vertex is 0.4 rad off the spot axis
    out = run_vertex(pp, position=(x, 0, 0, 1), normal=(0, 0, -1))
    rho, cos_half_theta, cos_half_phi = math.cos(0.4), math.cos(0.25), math.cos(0.5)
    spot = (rho - cos_half_phi) / (cos_half_theta - cos_half_phi)
    n_dot_l = math.cos(0.4)
    close(out["color0"][:3], [n_dot_l * spot] * 3)
    inside = run_vertex(pp, position=(0, 0, 0, 1), normal=(0, 0, -1))
    close(inside["color0"][:3], (1, 1, 1))
    outside = run_vertex(pp, position=(2 * math.tan(0.6), 0, 0, 1), normal=(0, 0, -1))
    close(outside["color0"][:3], (0, 0, 0))


STAGE0 = "Texture[0] = <Tex0>; ColorOp[0] = SelectArg1; ColorArg1[0] = Texture; Lighting = FALSE;"


def test_texcoordindex_picks_the_vertex_set():
    pp = lower(STAGE0 + "TexCoordIndex[0] = 2;")
    out = run_vertex(pp, texcoords={0: (9, 9, 0, 1), 2: (0.25, 0.75, 0, 1)})
    close(out["texcoord0"], (0.25, 0.75, 0, 1))


def test_texgen_camera_space_normal():
    world = "float4x4 Stretch = {2,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1};"
    states = STAGE0 + "TexCoordIndex[0] = CameraSpaceNormal; WorldTransform[0] = <Stretch>;"
    # normals transform by the inverse transpose: diag(0.5, 1, 1)
    out = run_vertex(lower(states, world), normal=(1, 1, 0))
    close(out["texcoord0"], (0.5, 1, 0, 1))
    out = run_vertex(lower(states + "NormalizeNormals = TRUE;", world), normal=(1, 1, 0))
    close(out["texcoord0"], (0.5 / math.sqrt(1.25), 1 / math.sqrt(1.25), 0, 1))


def test_texgen_camera_space_position():
    pp = lower(STAGE0 + "TexCoordIndex[0] = CameraSpacePosition;")
    close(run_vertex(pp, position=(1, 2, 3, 1))["texcoord0"], (1, 2, 3, 1))


def test_texgen_reflection_vector():
    pp = lower(STAGE0 + "TexCoordIndex[0] = CameraSpaceReflectionVector;")
    out = run_vertex(pp, position=(0, 0, 5, 1), normal=N)
    # I = (0, 0, 1); R = I - 2 (N.I) N = (0, 0, 1) + 1.6 (0, 0.6, -0.8)
    close(out["texcoord0"], (0, 0.96, -0.28, 1))


def test_texgen_spheremap():
    pp = lower(STAGE0 + "TexCoordIndex[0] = SphereMap;")
    out = run_vertex(pp, position=(0, 0, 5, 1), normal=N)
    # R = (0, 0.96, -0.28); m = 2 sqrt(0 + 0.9216 + 0.72^2) = 2.4
    close(out["texcoord0"], (0.5, 0.96 / 2.4 + 0.5, 0, 1))


def test_texture_transform_count2():
    matrix = "float4x4 Shift = {1,0,0,0, 0,1,0,0, 0,0,1,0, 0.5,0.25,0,1};"
    pp = lower(STAGE0 + "TextureTransformFlags[0] = Count2; TextureTransform[0] = <Shift>;",
               matrix)
    close(run_vertex(pp, texcoords={0: (0.1, 0.2, 0, 1)})["texcoord0"][:2], (0.6, 0.45))
    # without a count the matrix is not applied
    pp = lower(STAGE0 + "TextureTransform[0] = <Shift>;", matrix)
    close(run_vertex(pp, texcoords={0: (0.1, 0.2, 0, 1)})["texcoord0"][:2], (0.1, 0.2))


def test_vertex_fog_factor_from_eye_depth():
    proj = "float4x4 Persp = {1,0,0,0, 0,1,0,0, 0,0,1,1, 0,0,-1,0};"
    pp = lower("Lighting = FALSE; FogEnable = TRUE; FogVertexMode = Linear; FogStart = 0;"
               "FogEnd = 10; ProjectionTransform = <Persp>;", proj)
    close(run_vertex(pp, position=(1, 1, 4, 1))["fog"][0], 0.6)  # (10 - 4) / 10


@pytest.mark.parametrize("mode, density, factor", [
    ("Exp", 0.25, np.exp(-1.0)),          # e^-(4 * 0.25)
    ("Exp2", 0.125, np.exp(-0.25)),       # e^-((4 * 0.125)^2)
])
def test_vertex_fog_exponential_modes(mode, density, factor):
    proj = "float4x4 Persp = {1,0,0,0, 0,1,0,0, 0,0,1,1, 0,0,-1,0};"
    pp = lower(f"Lighting = FALSE; FogEnable = TRUE; FogVertexMode = {mode}; "
               f"FogDensity = {density}; ProjectionTransform = <Persp>;", proj)
    close(run_vertex(pp, position=(1, 1, 4, 1))["fog"][0], factor)


def test_range_fog_uses_the_distance_from_the_eye():
    """RangeFogEnable: the distance |(3, 0, 4)| = 5, not the depth 4: (10 - 5) / 10."""
    proj = "float4x4 Persp = {1,0,0,0, 0,1,0,0, 0,0,1,1, 0,0,-1,0};"
    pp = lower("Lighting = FALSE; FogEnable = TRUE; FogVertexMode = Linear; FogStart = 0;"
               "FogEnd = 10; RangeFogEnable = TRUE; ProjectionTransform = <Persp>;", proj)
    close(run_vertex(pp, position=(3, 0, 4, 1))["fog"][0], 0.5)


def test_render_state_comes_from_the_device_state():
    pp = lower("""Lighting = FALSE; AlphaBlendEnable = TRUE; SrcBlend = SrcAlpha;
        DestBlend = InvSrcAlpha; ZWriteEnable = FALSE; CullMode = None; AlphaTestEnable = TRUE;
        AlphaFunc = Greater; AlphaRef = 0x80; ColorWriteEnable = Red | Alpha;
        StencilEnable = TRUE; StencilPass = Replace; StencilRef = 3;""")
    rs = pp.render_state
    assert (rs.alpha_blend_enable, rs.src_blend, rs.dest_blend) == (True, "SRCALPHA", "INVSRCALPHA")
    assert (rs.z_write_enable, rs.z_enable, rs.cull_mode) == (False, True, "NONE")
    assert (rs.alpha_test_enable, rs.alpha_func, rs.alpha_ref) == (True, "GREATER", 0x80)
    assert rs.color_write_enable == 0x9
    assert (rs.stencil_enable, rs.stencil_pass, rs.stencil_ref) == (True, "REPLACE", 3)
