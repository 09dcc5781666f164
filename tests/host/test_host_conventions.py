"""The host conventions of the tools effect files were written for (issue 32), each a row of
the one binding table (effects/host/semantics.py): MikuMikuEffect's Object/CONTROLOBJECT,
RenderMonkey's predefined variables, the DirectX SDK samples' g_ names with their light
direction's sign, XNA BasicEffect's light; and what no convention gives stays unset, said."""
from __future__ import annotations

import math

import numpy as np
import pytest

import effects
from effects.host.runtime import render_frame
from effects.host.scene import Scene
from effects.host.semantics import bind_scene, binding_source, binding_table, host_would_set

CONVENTIONS = """
float4x4 model_world : CONTROLOBJECT < string name = "(self)"; >;
float3 self_pos : CONTROLOBJECT < string name = "(self)"; >;
float slider : CONTROLOBJECT < string name = "Controller.pmx"; string item = "Si"; >;
bool exists : CONTROLOBJECT < string name = "Controller.pmx"; >;
float3 CameraPosition : POSITION < string Object = "Camera"; >;
float3 CameraDirection : DIRECTION < string Object = "Camera"; >;
float3 LightDirection : DIRECTION < string Object = "Light"; >;
float4 MaterialDiffuse : DIFFUSE < string Object = "Geometry"; >;
float3 g_vLightDir;
float3 g_LightDir;
float4 g_LightDiffuse;
float g_fTime;
float3 g_vEyePt;
float4 g_MaterialDiffuseColor;
float fTime0_X : Time0_X;
float fTime0_1 : Time0_1;
float4 packed : Time0_X_Packed;
float2 dims : ViewportDimensions;
float2 inv : InverseViewportDimensions;
float3 DirLight0Direction;
float4 DiffuseColor;
technique T { pass P { } }
"""


@pytest.fixture(scope="module")
def bound(tmp_path_factory):
    path = tmp_path_factory.mktemp("conv") / "conv.fx"
    path.write_text(CONVENTIONS)
    effect = effects.load_effect(path)
    world = np.identity(4)
    world[3, :3] = (1.0, 2.0, 3.0)
    scene = Scene(time=130.0, world=world)       # 130 s: 10 s into RenderMonkey's 120 s cycle
    return effect, bind_scene(effect, scene, (64, 32)), scene


def test_mikumikueffect_objects(bound):
    effect, values, scene = bound
    assert np.array_equal(values["model_world"], scene.world.astype(np.float32))
    assert values["self_pos"].tolist() == [1.0, 2.0, 3.0]         # the world's translation
    # another object: 0 / false, MME's value for an object not loaded
    assert float(values["slider"]) == 0.0 and not bool(values["exists"])
    assert values["CameraPosition"].tolist() == [0.0, 0.0, 3.0]   # the default eye
    assert values["CameraDirection"].tolist() == [0.0, 0.0, -1.0]  # eye (0,0,3) to target 0
    # the light's travel direction: from (2, 2, 2) to the target, -(1, 1, 1)/sqrt 3
    assert values["LightDirection"] == pytest.approx([-1 / math.sqrt(3)] * 3)
    assert "MaterialDiffuse" not in values
    assert "model's material" in host_would_set(effect.parameter("MaterialDiffuse"))


def test_directx_sdk_names_point_their_light_direction_at_the_light(bound):
    effect, values, _ = bound
    # BasicHLSL lights with max(0, dot(N, g_LightDir)): toward the light, +(1, 1, 1)/sqrt 3
    assert values["g_vLightDir"] == pytest.approx([1 / math.sqrt(3)] * 3)
    assert values["g_LightDir"] == pytest.approx([1 / math.sqrt(3)] * 3)
    assert values["g_LightDiffuse"].tolist() == [1.0, 1.0, 1.0, 1.0]
    assert float(values["g_fTime"]) == 130.0
    assert values["g_vEyePt"].tolist() == [0.0, 0.0, 3.0]
    assert binding_source(effect.parameter("g_vLightDir")) == ("-LIGHTDIRECTION", "DirectX SDK name")
    assert "g_MaterialDiffuseColor" not in values           # no invented colours
    assert "material" in host_would_set(effect.parameter("g_MaterialDiffuseColor"))


def test_rendermonkey_predefined_variables(bound):
    _, values, _ = bound
    assert float(values["fTime0_X"]) == pytest.approx(10.0)
    assert float(values["fTime0_1"]) == pytest.approx(10.0 / 120.0)
    assert values["packed"] == pytest.approx([10.0, math.cos(10.0), math.sin(10.0), math.tan(10.0)],
                                             rel=1e-6)
    assert values["dims"].tolist() == [64.0, 32.0]
    assert values["inv"].tolist() == [1 / 64, 1 / 32]


def test_xna_basiceffect_light_zero_but_not_its_material(bound):
    effect, values, _ = bound
    assert values["DirLight0Direction"] == pytest.approx([-1 / math.sqrt(3)] * 3)  # travels
    assert "DiffuseColor" not in values
    assert "BasicEffect" in host_would_set(effect.parameter("DiffuseColor"))


def test_every_convention_is_a_row_of_the_binding_table():
    text = "\n".join(f"{s} {w}" for s, w in binding_table())
    for needle in ("TIME0_X", "VIEWDIRECTION", "CONTROLOBJECT", 'Object = "Camera"',
                   "g_LightDir", "DirLight0Direction", "BasicHLSL", "RenderMonkey",
                   "MikuMikuEffect", "Geometry"):
        assert needle in text, needle


TOWARD = """
float4x4 g_mWorldViewProjection;
float4x4 g_mWorld;
float3 g_vLightDir;
struct O { float4 p : POSITION; float3 n : TEXCOORD0; };
O vs(float4 p : POSITION, float3 n : NORMAL) { O o; o.p = mul(p, g_mWorldViewProjection);
    o.n = mul(n, (float3x3)g_mWorld); return o; }
float4 ps(float3 n : TEXCOORD0) : COLOR0 { return max(0, dot(normalize(n), g_vLightDir)); }
technique T { pass P { VertexShader = compile vs_2_0 vs(); PixelShader = compile ps_2_0 ps(); } }
"""


def test_an_sdk_style_effect_is_lit_from_the_scene_light_with_no_warning(tmp_path):
    path = tmp_path / "sdk.fx"
    path.write_text(TOWARD)
    light = {"light": {"position": [0, 0, 5]}}        # at the camera: the sphere's centre is lit
    frame = render_frame(effects.load_effect(path), "refrast", size=(32, 32), scene=light,
                         diagnose=True)
    assert frame.diagnostics == []
    # N·L = 1 at the sphere's centre (its normal (0, 0, 1) points at the light)
    assert tuple(frame.image[16, 16, :3]) == (255, 255, 255)


SPACES = """
float3 LWorld : DIRECTION < string Object = "DirectionalLight0"; string Space = "World"; >;
float3 LView : DIRECTION < string Object = "DirectionalLight0"; string Space = "VIEW"; >;
float4 PView : POSITION < string Object = "PointLight0"; string Space = "View"; >;
technique T { pass P { } }
"""


def test_a_dxsas_space_annotation_gives_the_light_in_that_space(tmp_path):
    path = tmp_path / "space.fx"
    path.write_text(SPACES)
    effect = effects.load_effect(path)
    values = bind_scene(effect, Scene(), (32, 32))
    third = 1 / math.sqrt(3)
    assert values["LWorld"] == pytest.approx([-third] * 3)
    # the default camera at (0, 0, 3) looking at the origin (D3DXMatrixLookAtLH): view x is
    # world -x, view z is world -z, y stays; the light at (2, 2, 2) is at (-2, 2, 1) in view
    assert values["LView"] == pytest.approx([third, -third, third])
    assert values["PView"] == pytest.approx([-2.0, 2.0, 1.0, 1.0])
