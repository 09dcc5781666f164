// In the style of the DirectX SDK's ConfigSystem sample: one vertex function and one pixel
// function compiled for each card class (vs_2_0 + ps_2_0 for DX9 cards, vs_1_1 + ps_1_1 for
// DX8 cards), and fixed function for the rest. Three point lights lit per vertex with the
// lit() intrinsic, as the SDK's vertex-lighting samples wrote it. The DX8 technique stands or
// falls on the vs_1_1 code fitting in vs_1_1's 128 slots (issue 31: it took 168 before the
// compiler used lit and packed its one-lane results; fxc fitted it).

float4x4 World               : WORLD;
float4x4 ViewProjection      : VIEWPROJECTION;
float4x4 View                : VIEW;
float4x4 Projection          : PROJECTION;
float4   EyePosition         : CAMERAPOSITION = { 0.0, 0.0, 3.0, 1.0 };

float4 LightPosition[3] = { { 2.0, 1.0, 2.0, 1.0 }, { -2.0, 1.0, 2.0, 1.0 },
                            { 0.0, -2.0, 2.0, 1.0 } };
float4 LightColor[3]    = { { 0.9, 0.3, 0.2, 1.0 }, { 0.2, 0.8, 0.3, 1.0 },
                            { 0.2, 0.3, 0.9, 1.0 } };
float4 LightAttenuation = { 1.0, 0.05, 0.02, 0.0 };   // constant, linear, quadratic
float4 MaterialDiffuse  = { 0.9, 0.9, 0.9, 1.0 };
float4 MaterialSpecular = { 0.5, 0.5, 0.5, 24.0 };     // w: the specular power
float4 Ambient          = { 0.1, 0.1, 0.1, 1.0 };

struct VS_OUT
{
    float4 Position : POSITION;
    float4 Diffuse  : COLOR0;
    float4 Specular : COLOR1;
};

VS_OUT LightVS(float4 Pos : POSITION, float3 Normal : NORMAL, uniform int Lights)
{
    VS_OUT o;
    float3 P = mul(Pos, World).xyz;
    float3 N = normalize(mul(Normal, (float3x3)World));
    float3 E = normalize(EyePosition.xyz - P);
    float3 diffuse = Ambient.rgb;
    float3 specular = 0;
    for (int i = 0; i < Lights; i++)
    {
        float3 L = LightPosition[i].xyz - P;
        float d2 = dot(L, L);
        float d = sqrt(d2);
        L = L / d;
        float atten = 1 / (LightAttenuation.x + LightAttenuation.y * d + LightAttenuation.z * d2);
        float3 H = normalize(L + E);
        float4 l = lit(dot(N, L), dot(N, H), MaterialSpecular.w);
        diffuse += LightColor[i].rgb * l.y * atten;
        specular += LightColor[i].rgb * l.z * atten;
    }
    o.Position = mul(float4(P, 1), ViewProjection);
    o.Diffuse = float4(saturate(diffuse * MaterialDiffuse.rgb), MaterialDiffuse.a);
    o.Specular = float4(saturate(specular * MaterialSpecular.rgb), 0);
    return o;
}

float4 LightPS(float4 Diffuse : COLOR0, float4 Specular : COLOR1) : COLOR
{
    return float4(saturate(Diffuse.rgb + Specular.rgb), Diffuse.a);
}

technique Config_dx9 < int Quality = 3; >
{
    pass P0
    {
        VertexShader = compile vs_2_0 LightVS(3);
        PixelShader  = compile ps_2_0 LightPS();
    }
}

technique Config_dx8 < int Quality = 2; >
{
    pass P0
    {
        VertexShader = compile vs_1_1 LightVS(3);
        PixelShader  = compile ps_1_1 LightPS();
    }
}

technique Config_ff < int Quality = 1; >
{
    pass P0
    {
        VertexShader = NULL;
        PixelShader  = NULL;
        WorldTransform[0]   = <World>;
        ViewTransform       = <View>;
        ProjectionTransform = <Projection>;
        Lighting = True;
        Ambient  = <Ambient>;
        LightEnable[0]   = True;
        LightType[0]     = Point;
        LightPosition[0] = <LightPosition[0]>;
        LightDiffuse[0]  = <LightColor[0]>;
        LightAttenuation0[0] = 1.0;
        LightRange[0]    = 100.0;
    }
}
