// lighting_ps20.fx -- bench_hlsl.py's realistic row: a 150-line ps_2_0 pixel function written
// the way DirectX 9 SDK samples wrote per-pixel lighting: a directional key light with a
// Blinn-Phong highlight, point fill lights in an unrolled loop over a compile-time count,
// normal/gloss/detail maps, options as compile-time arguments folded away, runtime ifs
// flattened to cmp. It fits ps_2_0 (61 of 64 arithmetic slots, 11 of 12 temporaries) and
// compiles without a warning. The function is `LightingPS`, lines 54-203 (27 of them comments
// or blank); the globals before it are not counted.

float3 KeyDirection = { -0.408, 0.816, -0.408 };   // toward the light
float4 KeyColor = { 1.0, 0.95, 0.85, 1.0 };
float4 LightPosition[3];          // world space, w unused
float4 LightColor[3];             // rgb colour, a intensity
float4 LightFalloff[3];           // x = 1 / range^2
float4 AmbientSky    = { 0.20, 0.22, 0.30, 1.0 };
float4 AmbientGround = { 0.10, 0.08, 0.05, 1.0 };
float4 MaterialDiffuse  = { 0.9, 0.8, 0.7, 1.0 };
float4 MaterialSpecular = { 0.5, 0.5, 0.5, 1.0 };
float  SpecularPower = 32.0;
float  BumpScale = 0.75;
float  RimPower = 3.0;
float4 RimColor = { 0.3, 0.3, 0.4, 1.0 };
float3 EyePosition;
float4 FogColor = { 0.5, 0.55, 0.6, 1.0 };
float  FogStart = 10.0;
float  FogInvRange = 0.02;
float  Exposure = 1.2;

texture DiffuseTexture;
texture NormalTexture;
texture GlossTexture;
texture DetailTexture;
texture EnvironmentTexture;
sampler2D DiffuseSampler = sampler_state { Texture = <DiffuseTexture>; MinFilter = Linear; MagFilter = Linear; };
sampler2D NormalSampler  = sampler_state { Texture = <NormalTexture>; MinFilter = Linear; MagFilter = Linear; };
sampler2D GlossSampler   = sampler_state { Texture = <GlossTexture>; MinFilter = Linear; MagFilter = Linear; };
sampler2D DetailSampler  = sampler_state { Texture = <DetailTexture>; MinFilter = Linear; MagFilter = Linear; };
samplerCUBE EnvironmentSampler = sampler_state { Texture = <EnvironmentTexture>; MinFilter = Linear; MagFilter = Linear; };
float  DetailScale = 8.0;
float  ReflectionAmount = 0.25;
float4 SelfIllumColor = { 0.0, 0.0, 0.0, 1.0 };

struct PS_INPUT
{
    float2 Tex      : TEXCOORD0;
    float3 Normal   : TEXCOORD1;   // world space, interpolated
    float3 Tangent  : TEXCOORD2;
    float3 Binormal : TEXCOORD3;
    float3 WorldPos : TEXCOORD4;
    float4 Color    : COLOR0;      // vertex colour (baked occlusion in alpha)
};

static const float3 Luminance = float3(0.299, 0.587, 0.114);

float4 LightingPS(PS_INPUT In,
                  uniform int  NumLights,
                  uniform bool UseNormalMap,
                  uniform bool UseGlossMap,
                  uniform bool UseDetail,
                  uniform bool UseEnvironment,
                  uniform bool UseRim,
                  uniform bool UseSelfIllum,
                  uniform int  DebugView,
                  uniform bool UseFog,
                  uniform bool Tonemap) : COLOR0
{
    // every option is a compile-time argument: the compiler folds the branches it turns off
    // ---- surface ---------------------------------------------------------------------------
    float4 albedo = tex2D(DiffuseSampler, In.Tex);
    albedo.rgb *= In.Color.rgb;
    float occlusion = In.Color.a;
    if (UseDetail)
    {
        // a tiled detail map, centred on grey so it darkens and brightens
        float3 detail = tex2D(DetailSampler, In.Tex * DetailScale).rgb;
        albedo.rgb *= detail * 2.0;
    }

    float3 N = In.Normal;
    if (UseNormalMap)
    {
        float3 bump = tex2D(NormalSampler, In.Tex).rgb * 2.0 - 1.0;
        bump.xy *= BumpScale;
        N = bump.x * In.Tangent + bump.y * In.Binormal + bump.z * In.Normal;
    }
    N = normalize(N);

    float gloss = 1.0;
    float power = SpecularPower;
    if (UseGlossMap)
    {
        float4 g = tex2D(GlossSampler, In.Tex);
        gloss = g.r;
        power = SpecularPower * g.a;
    }

    float3 P = In.WorldPos;
    float3 toEye = EyePosition - P;
    float eyeDistance = length(toEye);
    float3 V = toEye / eyeDistance;

    // ---- ambient: a hemisphere between ground and sky --------------------------------------
    float hemi = N.y * 0.5 + 0.5;
    float3 ambient = lerp(AmbientGround.rgb, AmbientSky.rgb, hemi) * occlusion;

    // ---- key light: directional, with a Blinn-Phong highlight -----------------------------
    float3 diffuse = 0;
    float3 specular = 0;
    float keyNdotL = dot(N, KeyDirection);
    if (keyNdotL > 0.0)
    {
        float3 H = normalize(KeyDirection + V);
        float NdotH = saturate(dot(N, H));
        diffuse = KeyColor.rgb * keyNdotL;
        specular = KeyColor.rgb * pow(NdotH, power);
    }

    // ---- fill lights: points, diffuse only, unrolled over the compile-time count -----------
    [unroll]
    for (int i = 0; i < 3; i++)
    {
        if (i < NumLights)
        {
            float3 toLight = LightPosition[i].xyz - P;
            float distance2 = dot(toLight, toLight);
            float3 L = toLight * rsqrt(distance2);
            float attenuation = saturate(1.0 - distance2 * LightFalloff[i].x);
            float NdotL = saturate(dot(N, L));
            diffuse += LightColor[i].rgb * (NdotL * attenuation);
        }
    }

    // ---- rim light -------------------------------------------------------------------------
    float3 rim = 0;
    if (UseRim)
    {
        float edge = 1.0 - saturate(dot(N, V));
        rim = RimColor.rgb * pow(edge, RimPower);
    }

    // ---- environment reflection with a Schlick-style fresnel term -------------------------
    float3 reflection = 0;
    if (UseEnvironment)
    {
        float3 R = reflect(-V, N);
        float fresnel = 1.0 - saturate(dot(N, V));
        fresnel = fresnel * fresnel;
        fresnel = lerp(0.04, 1.0, fresnel * fresnel * fresnel);
        reflection = texCUBE(EnvironmentSampler, R).rgb * (ReflectionAmount * fresnel * gloss);
    }

    // ---- combine ---------------------------------------------------------------------------
    float3 color = albedo.rgb * (ambient + diffuse * MaterialDiffuse.rgb);
    color += specular * MaterialSpecular.rgb * gloss;
    color += rim + reflection;
    if (UseSelfIllum)
    {
        // self-illumination where the albedo's alpha is low
        color = lerp(SelfIllumColor.rgb, color, albedo.a);
    }

    // ---- fog: linear in the eye distance ---------------------------------------------------
    if (UseFog)
    {
        float fog = saturate((eyeDistance - FogStart) * FogInvRange);
        color = lerp(color, FogColor.rgb, fog);
    }

    // ---- tone map --------------------------------------------------------------------------
    if (Tonemap)
    {
        color *= Exposure;
        float luma = dot(color, Luminance);
        color = color / (1.0 + luma);
    }
    else
    {
        color = saturate(color);
    }

    // ---- debug views (compile-time: the art path compiles one of these) --------------------
    if (DebugView == 1)
    {
        color = N * 0.5 + 0.5;
    }
    else if (DebugView == 2)
    {
        color = albedo.rgb;
    }
    else if (DebugView == 3)
    {
        color = diffuse + ambient;
    }
    else if (DebugView == 4)
    {
        color = specular;
    }

    // ---- output ----------------------------------------------------------------------------
    float4 result;
    result.rgb = color;
    result.a = albedo.a * MaterialDiffuse.a;
    return result;
}

technique Lighting_ps20
{
    pass P0
    {
        PixelShader = compile ps_2_0 LightingPS(2, true, true, true, false, false, false, 0, false, false);
    }
}
