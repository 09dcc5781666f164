// sdk9_style.fx -- veined, polished marble with a glowing outline, written the way DirectX 9
// SDK sample effects (EffectEdit, BasicHLSL, the DXSAS samples) were written. It exercises the
// DX9 effect language: `shared` / `static` / `uniform` / `extern` storage, float4x4 parameters
// with semantics, arrays, a struct type used both as a parameter and as shader I/O,
// annotations of every value type, texture2D / textureCUBE / texture3D, sampler2D /
// samplerCUBE / sampler3D = sampler_state { ... }, `Sampler[n] = (s);`, an HLSL vertex
// shader compiled with a uniform argument (`compile vs_1_1 MarbleVS(1)`), a ps_2_0 asm block
// with dcl / def / texld and a dependent read, alpha blending, stencil states and a
// multi-pass technique. (HLSL functions are captured, not compiled, by today's framework.)
//
// Techniques, best first:
//   Marble_ps20   DX9 (Radeon 9700), 2 passes: (1) HLSL vs_1_1 + ps_2_0 marble from a volume
//                 noise and a vein ramp (dependent read) plus a cube-map reflection, marking
//                 the object in the stencil buffer; (2) the same mesh pushed out along its
//                 normals, drawn additively only where the stencil is not marked: an outline
//   Marble_ps11   DX8 (GeForce3, Radeon 8500): asm vs_1_1 + ps.1.1, the vein ramp read
//                 through texreg2gb from the volume noise, plus the reflection
//   Marble_dx7    DX7 (GeForce2): fixed function, a 2D vein texture x vertex light + cube map
//                 by CameraSpaceReflectionVector
//   Marble_dx6    anything: fixed function, the 2D vein texture x vertex light
//
// Technique annotations: `int Quality` (higher looks better) and `float Cost` (texture reads
// + arithmetic slots, or texture stages, per pixel, summed over passes). Texture annotations
// follow fxfiles/README.md.

//----------------------------------------------------------------------------------------------
// Parameters

// Shared between effects created with the same pool: the camera.
shared float4x4 ViewProjection : VIEWPROJECTION;
shared float4x4 View           : VIEW;
shared float4x4 Projection     : PROJECTION;
shared float4   EyePosition    : CAMERAPOSITION = { 0.0, 0.0, 3.0, 1.0 };

uniform float4x4 World               : WORLD;
uniform float4x4 WorldViewProjection : WORLDVIEWPROJECTION;

extern float4 LightDirection : LIGHTDIRECTION
<
    string UIName = "Light direction (world, the way the light travels)";
    string UIWidget = "Direction";
    bool   Normalize = true;
    float3 Default = { 0.577, -0.577, -0.577 };
> = { 0.577, -0.577, -0.577, 0.0 };

extern float4 LightColor : LIGHTCOLOR = { 1.0, 0.97, 0.9, 1.0 };

// Every annotation value type in one place.
float NoiseScale
<
    string UIName   = "Vein frequency";
    string UIWidget = "Slider";
    float  UIMin    = 0.25;
    float  UIMax    = 4.0;
    float  UIStep   = 0.05;
    int    UIOrder  = 1;
    bool   UIVisible = true;
    float2 UIRange  = { 0.25, 4.0 };
    float4 UIColor  = { 0.9, 0.9, 0.9, 1.0 };
    int2   UIGrid   = { 4, 4 };
> = 1.5;

// Not visible to the application; used by the HLSL vertex shader.
static float ShellThickness = 0.04;

// Two outline colours, blended by the vertex light.
float4 RimColors[2] =
{
    { 1.0, 0.55, 0.2, 0.8 },
    { 0.2, 0.45, 1.0, 0.8 }
};

float Weights[3] = { 0.25, 0.5, 0.25 };

struct MaterialDesc
{
    float4 Diffuse;
    float4 Reflectivity;
    float  Power;
};

MaterialDesc Marble
<
    string UIName = "Marble material";
> = { { 0.95, 0.93, 0.9, 1.0 }, { 0.25, 0.25, 0.25, 1.0 }, 32.0 };

// The reflectivity again as a plain vector, for the asm shaders' constant registers.
float4 Reflectivity = { 0.25, 0.25, 0.25, 1.0 };

texture3D MarbleNoise
<
    string Procedural = "noise3d:32";
    string Type = "3D";
    string Format = "L8";
    int Width = 32;
    int Height = 32;
    int Depth = 32;
>;

textureCUBE Environment
<
    string Procedural = "sky_cube:64";
    string Type = "CUBE";
    string Format = "X8R8G8B8";
    int Width = 64;
    int Height = 64;
>;

texture2D VeinRamp
<
    string ResourceName = "textures/marble_vein.png";
    string Type = "2D";
>;

sampler3D NoiseSampler = sampler_state
{
    Texture = <MarbleNoise>;
    MinFilter = Linear;
    MagFilter = Linear;
    MipFilter = None;
    AddressU = Wrap;
    AddressV = Wrap;
    AddressW = Wrap;
};

samplerCUBE EnvSampler = sampler_state
{
    Texture = <Environment>;
    MinFilter = Linear;
    MagFilter = Linear;
    AddressU = Clamp;
    AddressV = Clamp;
    AddressW = Clamp;
};

sampler2D VeinSampler = sampler_state
{
    Texture = <VeinRamp>;
    MinFilter = Linear;
    MagFilter = Linear;
    MipFilter = Linear;
    AddressU = Wrap;
    AddressV = Clamp;
};

//----------------------------------------------------------------------------------------------
// HLSL vertex shader

struct VS_OUTPUT
{
    float4 Position : POSITION;
    float4 Diffuse  : COLOR0;
    float3 NoisePos : TEXCOORD0;    // object-space position, scaled: the marble's "P"
    float3 Reflect  : TEXCOORD1;    // world-space reflection vector
    float2 Tex      : TEXCOORD2;
};

// Shell = 1: the object itself; Shell = 2: pushed out along the normals for the outline.
VS_OUTPUT MarbleVS(float4 Pos    : POSITION,
                   float3 Normal : NORMAL,
                   float2 Tex    : TEXCOORD0,
                   uniform int Shell)
{
    VS_OUTPUT o;
    float4 p = Pos;
    if (Shell > 1)
        p.xyz += Normal * ShellThickness;

    float3 worldPos = mul(p, World).xyz;
    float3 N = normalize(mul(Normal, (float3x3)World));
    float3 E = normalize(EyePosition.xyz - worldPos);

    o.Position = mul(float4(worldPos, 1.0), ViewProjection);
    o.Diffuse  = saturate(dot(N, -LightDirection.xyz)) * LightColor * Marble.Diffuse;
    o.Diffuse.a = 1.0;
    o.NoisePos = Pos.xyz * NoiseScale;
    o.Reflect  = reflect(-E, N);
    o.Tex      = Tex;
    return o;
}

//----------------------------------------------------------------------------------------------
// Techniques, best first

technique Marble_ps20
<
    string Description = "HLSL vs_1_1 + asm ps_2_0 marble, stencil outline pass";
    int Quality = 4;
    float Cost = 13.0;
>
{
    pass Marble
    <
        string Description = "the marble; marks its pixels with stencil 1";
    >
    {
        VertexShader = compile vs_1_1 MarbleVS(1);

        Sampler[0] = (NoiseSampler);
        Sampler[1] = (EnvSampler);
        Sampler[2] = (VeinSampler);
        PixelShaderConstantF[1] = <Reflectivity>;

        PixelShader = asm
        {
            ps_2_0
            dcl v0                      // lit diffuse
            dcl t0.xyz                  // noise coordinates
            dcl t1.xyz                  // reflection vector
            dcl_volume s0
            dcl_cube   s1
            dcl_2d     s2
            def c0, 4.0, 0.5, 0.0, 1.0  // (turbulence, ramp row, 0, 1)
            // c1 = reflectivity

            texld r0, t0, s0            // r0.x = noise
            mov r1.yzw, c0              // ramp row 0.5
            mad r1.x, r0.x, c0.x, t0.y  // stripe = 4 * noise + y
            frc r1.x, r1.x
            texld r2, r1, s2            // dependent read: vein colour
            texld r3, t1, s1            // environment at the reflection vector
            mul r2, r2, v0              // lit marble
            mad r2.xyz, r3, c1, r2      // + reflection * reflectivity
            mov r2.w, c0.w
            mov oC0, r2
        };

        ZEnable = True;
        ZWriteEnable = True;
        CullMode = CCW;
        StencilEnable = True;
        StencilFunc = Always;
        StencilRef = 1;
        StencilMask = 0xffffffff;
        StencilWriteMask = 0xffffffff;
        StencilPass = Replace;
        StencilFail = Keep;
        StencilZFail = Keep;
    }

    pass Outline
    <
        string Description = "the pushed-out shell, added where the stencil is not 1";
    >
    {
        VertexShader = compile vs_1_1 MarbleVS(2);
        PixelShaderConstantF[0] = <RimColors>;      // c0, c1

        PixelShader = asm
        {
            ps_2_0
            dcl v0
            lrp r0, v0.x, c0, c1        // lit side takes RimColors[0], dark side [1]
            mov oC0, r0
        };

        ZWriteEnable = False;
        StencilFunc = NotEqual;
        StencilPass = Keep;
        AlphaBlendEnable = True;
        SrcBlend = SrcAlpha;
        DestBlend = One;
        BlendOp = Add;
    }
}

technique Marble_ps11
<
    string Description = "asm vs_1_1 + ps.1.1, vein ramp by texreg2gb";
    int Quality = 3;
    float Cost = 5.0;
>
{
    pass P0
    {
        VertexShaderConstantF[0] = <WorldViewProjection>;
        VertexShaderConstantF[4] = <World>;
        VertexShaderConstantF[8] = <EyePosition>;
        VertexShaderConstantF[9] = <LightDirection>;
        VertexShaderConstantF[10] = <LightColor>;
        VertexShaderConstantF[11] = <NoiseScale>;

        VertexShader = asm
        {
            vs_1_1
            dcl_position  v0
            dcl_normal    v3
            // c0-c3 world*view*projection, c4-c7 world, c8 eye, c9 light direction,
            // c10 light colour, c11.x noise scale
            def c12, 0.0, 0.0, 0.0, 0.0

            m4x4 oPos, v0, c0
            m4x4 r0, v0, c4             // world position
            m3x3 r5.xyz, v3, c4         // world normal
            dp3 r5.w, r5, r5
            rsq r5.w, r5.w
            mul r5.xyz, r5, r5.w

            dp3 r1.x, r5, -c9           // N.L
            max r1.x, r1.x, c12.x       // no light from behind
            mul oD0, c10, r1.x          // lit diffuse

            mul oT0.xyz, v0, c11.x      // noise coordinates

            add r2.xyz, c8, -r0         // toward the eye
            dp3 r2.w, r2, r2
            rsq r2.w, r2.w
            mul r2.xyz, r2, r2.w
            dp3 r3.x, r5, r2
            add r3.x, r3.x, r3.x
            mad oT1.xyz, r5, r3.x, -r2  // reflection vector
        };

        Texture[0] = <MarbleNoise>;
        Texture[1] = <Environment>;
        Texture[2] = <VeinRamp>;
        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
        MinFilter[1] = Linear;
        MagFilter[1] = Linear;
        MinFilter[2] = Linear;
        MagFilter[2] = Linear;
        PixelShaderConstantF[1] = <Reflectivity>;

        PixelShader = asm
        {
            ps.1.1
            tex t0                      // noise (volume)
            tex t1                      // environment (cube), reflection vector
            texreg2gb t2, t0            // vein ramp at (t0.g, t0.b)

            mul r0, t2, v0              // lit marble
            mad r0, t1, c1, r0          // + reflection * reflectivity
        };
    }
}

technique Marble_dx7
<
    string Description = "fixed function: vein texture x vertex light + cube reflection";
    int Quality = 2;
    float Cost = 2.0;
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
        LightDirection[0] = <LightDirection>;
        LightDiffuse[0]   = <LightColor>;
        MaterialDiffuse   = { 0.95, 0.93, 0.9, 1.0 };

        Sampler[0]   = (VeinSampler);
        ColorOp[0]   = Modulate;
        ColorArg1[0] = Texture;
        ColorArg2[0] = Diffuse;

        Texture[1]       = <Environment>;
        TexCoordIndex[1] = CameraSpaceReflectionVector;
        TextureTransformFlags[1] = Count3;
        ColorOp[1]   = BlendFactorAlpha; // 0.25 * reflection + 0.75 * lit marble
        ColorArg1[1] = Texture;
        ColorArg2[1] = Current;
        TextureFactor = 0x40ffffff;     // alpha 0x40: reflectivity 0.25
        MinFilter[1] = Linear;
        MagFilter[1] = Linear;

        ColorOp[2] = Disable;
    }
}

technique Marble_dx6
<
    string Description = "fixed function: vein texture x vertex light";
    int Quality = 1;
    float Cost = 1.0;
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
        LightDirection[0] = <LightDirection>;
        LightDiffuse[0]   = <LightColor>;
        MaterialDiffuse   = { 0.95, 0.93, 0.9, 1.0 };

        Texture[0]   = <VeinRamp>;
        ColorOp[0]   = Modulate;
        ColorArg1[0] = Texture;
        ColorArg2[0] = Diffuse;
        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
        MipFilter[0] = Linear;
        ColorOp[1]   = Disable;
    }
}
