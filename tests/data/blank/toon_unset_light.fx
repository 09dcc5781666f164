float4x4 matWorldViewProjection : WorldViewProjection;
float4x4 matWorld : World;
float3 vLightDirection;
float4 cBase = float4(1.0, 0.5, 0.2, 1.0);
struct VS_OUT { float4 pos : POSITION; float3 n : TEXCOORD0; };
VS_OUT vs_main(float4 p : POSITION, float3 n : NORMAL)
{
    VS_OUT o;
    o.pos = mul(p, matWorldViewProjection);
    o.n = mul(n, (float3x3)matWorld);
    return o;
}
float4 ps_main(float3 n : TEXCOORD0) : COLOR0
{
    float d = dot(normalize(n), -vLightDirection);
    float band = d > 0.5 ? 1.0 : (d > 0.1 ? 0.6 : 0.0);
    return cBase * band;
}
technique Toon
{
    pass p0
    {
        VertexShader = compile vs_2_0 vs_main();
        PixelShader = compile ps_2_0 ps_main();
    }
}
