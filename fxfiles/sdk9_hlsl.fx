// sdk9_hlsl.fx -- a textured, lit, specular object written the way DirectX 9 SDK samples wrote
// HLSL effects (BasicHLSL): one vertex function and one pixel function, compiled for each
// hardware generation by the technique that uses them, the best first. `uniform bool
// Specular` is a compile-time argument: the ps_2_0 build has the specular term, the ps_1_x
// builds leave it out (fxc could not fit pow() there). Each compile is judged against its own
// target: ps_1_4 runs on the Radeon 8500, ps_1_1 on the GeForce3/4 Ti, and DX7 cards fall back
// to the fixed-function technique (written by hand, as the SDK samples did for DX7 cards).
//
// `uniform bool Biased` is the DX8 half of the chain: a ps_1_x shader cannot renormalise
// (no rsq) and ps_1_1-1_3 read a texture coordinate as a value through `texcoord`, which clamps
// it to [0, 1]; so the vs_1_1 builds write the unit normal biased into [0, 1] and the pixel
// function expands it with 2 * n - 1, which compiles to the _bx2 source modifier.

float4x4 WorldViewProjection : WORLDVIEWPROJECTION;
float4x4 World               : WORLD;
float4x4 View                : VIEW;
float4x4 Projection          : PROJECTION;
float4   EyePosition         : CAMERAPOSITION = { 0.0, 0.0, 3.0, 1.0 };

// Toward the light, world space: above, left and in front (the camera is at +z). Named so that
// no host binds it by name: a scene's LIGHTDIRECTION is the way the light travels
// (D3DLIGHT9.Direction), the opposite of what the pixel function reads.
float3 ToLight = { -0.408, 0.816, 0.408 };
float4 MaterialDiffuse = { 0.9, 0.75, 0.55, 1.0 };
float4 MaterialAmbient = { 0.12, 0.12, 0.16, 1.0 };
float  SpecularPower = 24.0;

texture DiffuseTexture
<
    string ResourceName = "textures/stones_base.png";
>;

sampler2D DiffuseSampler = sampler_state
{
    Texture = <DiffuseTexture>;
    MinFilter = Linear;
    MagFilter = Linear;
    MipFilter = Linear;
};

struct VS_OUTPUT
{
    float4 Position : POSITION;
    float2 Tex      : TEXCOORD0;
    float3 Normal   : TEXCOORD1;   // world space
    float3 ToEye    : TEXCOORD2;   // world space
};

VS_OUTPUT SceneVS(float4 Pos : POSITION, float3 Normal : NORMAL, float2 Tex : TEXCOORD0,
                  uniform bool Biased)
{
    VS_OUTPUT o;
    float3 worldPos = mul(Pos, World).xyz;
    float3 n = mul(Normal, (float3x3)World);
    o.Position = mul(Pos, WorldViewProjection);
    o.Tex      = Tex;
    o.Normal   = Biased ? normalize(n) * 0.5 + 0.5 : n;
    o.ToEye    = EyePosition.xyz - worldPos;
    return o;
}

float4 ScenePS(float2 Tex : TEXCOORD0, float3 Normal : TEXCOORD1, float3 ToEye : TEXCOORD2,
               uniform bool Specular) : COLOR0
{
    // ps_2_0 renormalises the interpolated normal; ps_1_x expands the biased one (_bx2)
    float3 N = Specular ? normalize(Normal) : 2 * Normal - 1;
    float diffuse = saturate(dot(N, ToLight));
    float4 color = tex2D(DiffuseSampler, Tex) * (MaterialAmbient + MaterialDiffuse * diffuse);
    if (Specular)
    {
        float3 H = normalize(ToLight + normalize(ToEye));
        color.rgb += pow(saturate(dot(N, H)), SpecularPower) * 0.5;
    }
    color.a = 1.0;
    return color;
}

technique Scene_ps20
<
    string Description = "vs_2_0 + ps_2_0, with the specular term";
>
{
    pass P0
    {
        VertexShader = compile vs_2_0 SceneVS(false);
        PixelShader  = compile ps_2_0 ScenePS(true);
    }
}

technique Scene_ps14
<
    string Description = "vs_1_1 + ps_1_4, diffuse only";
>
{
    pass P0
    {
        VertexShader = compile vs_1_1 SceneVS(true);
        PixelShader  = compile ps_1_4 ScenePS(false);
    }
}

technique Scene_ps11
<
    string Description = "vs_1_1 + ps_1_1, diffuse only";
>
{
    pass P0
    {
        VertexShader = compile vs_1_1 SceneVS(true);
        PixelShader  = compile ps_1_1 ScenePS(false);
    }
}

technique Scene_ff
<
    string Description = "fixed function: the texture times the vertex-lit material";
>
{
    pass P0
    {
        VertexShader = NULL;
        PixelShader  = NULL;
        WorldTransform[0]   = <World>;
        ViewTransform       = <View>;
        ProjectionTransform = <Projection>;

        Lighting          = True;
        LightEnable[0]    = True;
        LightType[0]      = Directional;
        LightDirection[0] = { 0.408, -0.816, -0.408 };  // the way the light travels
        LightDiffuse[0]   = { 1.0, 1.0, 1.0, 1.0 };
        Ambient           = 0x001f1f28;
        MaterialDiffuse   = { 0.9, 0.75, 0.55, 1.0 };
        MaterialAmbient   = { 1.0, 1.0, 1.0, 1.0 };

        Sampler[0]   = (DiffuseSampler);
        ColorOp[0]   = Modulate;
        ColorArg1[0] = Texture;
        ColorArg2[0] = Diffuse;
        ColorOp[1]   = Disable;
    }
}
