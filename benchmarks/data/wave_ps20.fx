// bench_viewer.py's animated effect: a lit sphere whose colour runs in a wave with TIME
// (ps_2_0), colour = Tint * (0.25 + 0.75 max(N.L, 0)) * (0.5 + 0.5 sin(2 pi (u + TIME * Speed)))
float4x4 WorldViewProjection : WORLDVIEWPROJECTION;
float4x4 World : WORLD;
float3 LightDirection : LIGHTDIRECTION = { -0.5, -0.5, -0.7 };
float Time : TIME;
float Speed < string UIName = "Speed"; float UIMin = 0.0; float UIMax = 2.0; > = 0.5;
float3 Tint < string UIWidget = "Color"; > = { 1.0, 0.6, 0.3 };
struct VOut { float4 pos : POSITION; float3 normal : TEXCOORD0; float2 uv : TEXCOORD1; };
VOut vs(float4 p : POSITION, float3 n : NORMAL, float2 uv : TEXCOORD0)
{
    VOut o;
    o.pos = mul(p, WorldViewProjection);
    o.normal = mul(n, (float3x3)World);
    o.uv = uv;
    return o;
}
float4 ps(VOut i) : COLOR
{
    float lit = 0.25 + 0.75 * max(dot(normalize(i.normal), -LightDirection), 0.0);
    float wave = 0.5 + 0.5 * sin(6.2831853 * (i.uv.x + Time * Speed));
    return float4(Tint * lit * wave, 1.0);
}
technique Wave { pass P { VertexShader = compile vs_2_0 vs(); PixelShader = compile ps_2_0 ps(); } }
