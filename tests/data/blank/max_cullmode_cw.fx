// Ours, in the shape of a 3ds Max DirectX material (its SAS semantics and UI annotations):
// 3ds Max's meshes are wound the other way round, so its effects set CullMode = CW; on
// Direct3D's clockwise-front meshes that culls the faces toward the camera.
float4x4 WorldViewProj : WorldViewProjection < string UIWidget = "None"; >;
float4x4 WorldIT : WorldInverseTranspose < string UIWidget = "None"; >;
float3 LightDir : Direction < string UIName = "Light Direction"; string Object = "TargetLight"; > = { 0.0, 0.0, 1.0 };
float4 DiffuseColor < string UIName = "Diffuse"; string UIWidget = "Color"; > = { 0.8, 0.3, 0.2, 1.0 };
struct VS_OUT { float4 pos : POSITION; float4 col : COLOR0; };
VS_OUT vs_main(float4 p : POSITION, float3 n : NORMAL)
{
    VS_OUT o;
    o.pos = mul(p, WorldViewProj);
    float3 N = normalize(mul(n, (float3x3)WorldIT));
    o.col = DiffuseColor * (0.2 + 0.8 * saturate(dot(N, -LightDir)));
    return o;
}
float4 ps_main(float4 c : COLOR0) : COLOR0 { return c; }
technique Max
{
    pass p0
    {
        CullMode = CW;
        VertexShader = compile vs_2_0 vs_main();
        PixelShader = compile ps_2_0 ps_main();
    }
}
