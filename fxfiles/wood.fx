// wood.fx -- the DirectX 9 HLSL wood effect of Chas Boyd, "Hardware Shading with Direct3D"
// (chapter 5), section "DirectX 9 High Level Shading Language": "a very simple wood shader from
// the Renderman Companion ... This should run in 1 pass of the pixel shader 2.0 model".
//
// The chapter prints the parameters, helpers and the pixel shader function whole, but in the
// pre-release DirectX 9 HLSL of 2002 and without a technique. This file is the closest
// faithful rendition in released DirectX 9 effect syntax. Names, order, constants, comments
// and the arithmetic are the printed ones; the changes are only these:
//   * the first printed line `fx.2.0` is kept as a comment (it is not effect syntax);
//   * `vec3`/`vec4` -> `float3`/`float4`, `volumetexture` -> `texture3D`, `len` -> `length`,
//     `frc` -> `frac` (the released names of the same types and intrinsics);
//   * `sample3d(noise, PP)` -> `tex3D(NoiseSampler, PP).xyz` and `sample1d(noise, r)` ->
//     `tex3D(NoiseSampler, float3(r, 0.0f, 0.0f)).x`: released HLSL samples through a sampler,
//     so a `sampler3D NoiseSampler` bound to `noise` was added; a volume texture has no 1D
//     view, so the 1D lookup reads the volume's first row;
//   * `float point_scale = 1.0f, turbulence = 1.0f;` split into two declarations;
//   * `PS_INPUT.Color` is float4, not vec3 (the shader reads `v.Color.a`);
//   * the missing `;` after `return diffuse_color * dot(N, L)` was added, and the stray `;`
//     after the closing brace of `Wood` removed;
//   * OCR spacing such as `float  ringscale` and `return  o` collapsed to one blank;
//   * `noise` carries a `Procedural` annotation (see fxfiles/README.md) so a loader can make it.
// Added below the printed code (marked "added"): a WorldViewProjection parameter, a vertex
// shader function that feeds PS_INPUT, and the technique `Wood_ps20` (one pass, vs_1_1 +
// ps_2_0). There is deliberately no fallback chain: this file is a transcription.
// The helper named `smoothstep` is the printed Hermite form; it shadows the HLSL intrinsic
// of the same name inside this file.
// Parameters with no initializer (the colours, L and I) are set by the application, as in
// the chapter; L and I are directions in the object space the vertex shader passes on.
//
// Printed first line:
// fx.2.0

//////////////////////////////////////////////////////////////////////////////
// Effect parameters /////////////////////////////////////////////////////////
//////////////////////////////////////////////////////////////////////////////

float ringscale = 10.0f;
float point_scale = 1.0f;
float turbulence = 1.0f;

float3 lightwood = float3(0.3f, 0.12f, 0.03f);
float3 darkwood  = float3(0.05f, 0.01f, 0.005f);

float Ka = 0.2;
float Kd = 0.4;
float Ks = 0.6;
float roughness = 0.1;

float3 ambient_color;
float3 diffuse_color;
float3 specular_color;

texture3D noise
<
    string Procedural = "noise3d:32";   // added: 32x32x32 L8 value noise
>;

// added: released HLSL samples textures through samplers
sampler3D NoiseSampler = sampler_state
{
    Texture = <noise>;
    MinFilter = Linear;
    MagFilter = Linear;
    MipFilter = None;
    AddressU = Wrap;
    AddressV = Wrap;
    AddressW = Wrap;
};

float3 L;
float3 I;

// added: the transform the vertex shader needs
float4x4 WorldViewProjection : WORLDVIEWPROJECTION;


//////////////////////////////////////////////////////////////////////////////
// Renderman-like helper functions ///////////////////////////////////////////
//////////////////////////////////////////////////////////////////////////////

float smoothstep( float a, float b, float s)
{
    float s2 = s * s;
    float s3 = s * s2;

    float sV1 = 2.0f * s3 - 3.0f * s2 + 1.0f;
    float sT1 = s3 - 2.0f * s2 + s;
    float sV2 = -2.0f * s3 + 3.0f * s2;
    float sT2 = s3 - s2;

    return s < 0.0f ? a : s > 1.0f ? b : sV1 * a + sT1 + sV2 * b + sT2;
}

float3 diffuse(float3 N)
{
    return diffuse_color * dot(N, L);
}
float3 specular(float3 N, float3 eye, float roughness)
{
    float3 H = (L + eye) / length(L + eye);
    return specular_color * pow(dot(H, N), 1 / roughness);
}



//////////////////////////////////////////////////////////////////////////////
// Wood Shader ///////////////////////////////////////////////////////////////
//////////////////////////////////////////////////////////////////////////////

struct PS_INPUT
{
    float4 Color    : COLOR0;
    float3 Position : TEXCOORD0;
    float3 Normal   : TEXCOORD1;
};

struct PS_OUTPUT
{
    float4 Color : COLOR0;
};



PS_OUTPUT Wood(const PS_INPUT v)
{
    /* Perturb P to add irregularity */
    float3 PP = v.Position * point_scale;
    PP += tex3D(NoiseSampler, PP).xyz * turbulence;

    /* Compute radial distance r from PP to axis of tree */
    float r = sqrt(PP.y * PP.y + PP.z * PP.z);

    /* Map radial distance r into ring position [0,1] */
    r *= ringscale;
    r += abs(tex3D(NoiseSampler, float3(r, 0.0f, 0.0f)).x * turbulence);
    r  = frac(r);

    /* Use r to select wood color */
    r = smoothstep(0.0f, 0.8f, r) - smoothstep(0.83f, 1.0f , r);

    /* Shade using r to vary brightness of wood grain */
    PS_OUTPUT o;

    o.Color.rgb = (ambient_color * Ka + diffuse(v.Normal) * Kd) *
        lerp(lightwood, darkwood, r) * v.Color.a +
        specular(v.Normal, -I, roughness) * (Ks * (0.3f * r + 0.7f));

    o.Color.a = v.Color.a;

    return o;
}


//////////////////////////////////////////////////////////////////////////////
// added: vertex shader and technique ////////////////////////////////////////
//////////////////////////////////////////////////////////////////////////////

struct VS_OUTPUT
{
    float4 Position  : POSITION;
    float4 Color     : COLOR0;
    float3 ShadePos  : TEXCOORD0;   // object-space position: the "P" the wood is carved from
    float3 Normal    : TEXCOORD1;   // object-space normal
};

VS_OUTPUT WoodVS(float4 Position : POSITION, float3 Normal : NORMAL, float4 Color : COLOR0)
{
    VS_OUTPUT o;
    o.Position = mul(Position, WorldViewProjection);
    o.Color    = Color;
    o.ShadePos = Position.xyz;
    o.Normal   = normalize(Normal);
    return o;
}

// One pass of vs_1_1 + ps_2_0: a Radeon 9700 class card (DirectX 9).
technique Wood_ps20
<
    int Quality = 4;
    float Cost = 3.0;
>
{
    pass p0
    {
        VertexShader = compile vs_1_1 WoodVS();
        PixelShader  = compile ps_2_0 Wood();
    }
}


//////////////////////////////////////////////////////////////////////////////
// added: the rings the shader was written for ///////////////////////////////
//////////////////////////////////////////////////////////////////////////////
//
// The printed `smoothstep` is not RenderMan's: it takes s as is (not (s - a) / (b - a)) and
// treats a and b as the end values, with unit tangents added. So in `Wood` the line
//     r = smoothstep(0.0f, 0.8f, r) - smoothstep(0.83f, 1.0f, r);
// gives 0.63 sV2(r) - 0.83, between -0.83 and -0.2 (sV2 = 3 r^2 - 2 r^3): lerp(lightwood,
// darkwood, r) then extrapolates past lightwood, and the grain is a faint sawtooth in the
// light colour (the ring's extremes 1.45 x apart) instead of the dark rings with thin light
// bands of the Renderman Companion shader. `WoodRings` is `Wood` with RenderMan's smoothstep
// (0 below a, 1 above b, the Hermite 3t^2 - 2t^3 of t = (s - a) / (b - a) between); cards
// still select Wood_ps20, the transcription, which comes first. With this file's noise
// volume (noise3d: 4 lattice cells per unit, 3 octaves) a turbulence of 1 moves the point by
// up to 10 rings and dissolves them into the noise's contour lines; about 0.1 keeps wood
// (`--set turbulence=0.1`).

float ring_step(float a, float b, float s)
{
    float t = saturate((s - a) / (b - a));
    return t * t * (3.0f - 2.0f * t);
}

PS_OUTPUT WoodRings(const PS_INPUT v)
{
    float3 PP = v.Position * point_scale;
    PP += tex3D(NoiseSampler, PP).xyz * turbulence;
    float r = sqrt(PP.y * PP.y + PP.z * PP.z);
    r *= ringscale;
    r += abs(tex3D(NoiseSampler, float3(r, 0.0f, 0.0f)).x * turbulence);
    r  = frac(r);
    r = ring_step(0.0f, 0.8f, r) - ring_step(0.83f, 1.0f, r);
    PS_OUTPUT o;
    o.Color.rgb = (ambient_color * Ka + diffuse(v.Normal) * Kd) *
        lerp(lightwood, darkwood, r) * v.Color.a +
        specular(v.Normal, -I, roughness) * (Ks * (0.3f * r + 0.7f));
    o.Color.a = v.Color.a;
    return o;
}

technique WoodRings_ps20
<
    int Quality = 4;
    float Cost = 3.0;
>
{
    pass p0
    {
        VertexShader = compile vs_1_1 WoodVS();
        PixelShader  = compile ps_2_0 WoodRings();
    }
}
