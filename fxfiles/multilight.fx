// multilight.fx -- one look, four coloured directional lights on a diffuse surface, down the
// hardware generations:
//   MultiLight_ps30   DX9 SM3 (GeForce 6800, the reference device): vs_3_0 + ps_3_0, one
//                     `loop aL, i0` over the four lights, per pixel, reading each light's
//                     direction c[aL] and colour c[aL + 4] by relative addressing
//   MultiLight_ps20   DX9 ps_2_0 (Radeon 9700, GeForce FX): the same sum, unrolled, per pixel
//   MultiLight_ff     DX6-DX8: fixed-function vertex lighting with the same four lights
//
// colour = Ambient + sum over lights i of LightRGB_i * sat(N . L_i), with N the unit surface
// normal (world space) and L_i the unit direction towards light i. The fixed-function path
// computes it per vertex (D3D's directional lights: LightDirection is the direction the light
// travels, so it is -L_i) and interpolates; the shader paths per pixel.
// `int Quality` orders the techniques best first; `float Cost` is instruction slots per pixel.
// Vertex input: position, normal. Matrices loaded with VertexShaderConstantF are read by
// m4x4/m3x3 as rows of the transpose (the runtime loads them that way, as D3DX does).

float4x4 WorldViewProjection : WORLDVIEWPROJECTION;
float4x4 World               : WORLD;
float4x4 View                : VIEW;
float4x4 Projection          : PROJECTION;

// unit directions towards each light, world space (ToLight and LightRGB, not LightDir and
// LightColor: a host binds LightDir0 and LightColor0 to its own light by name, XNA style,
// and these four lights are the file's)
float4 ToLight0 = { 0.8, 0.6, 0.0, 0.0 };
float4 ToLight1 = { -0.8, 0.6, 0.0, 0.0 };
float4 ToLight2 = { 0.0, -0.6, 0.8, 0.0 };
float4 ToLight3 = { 0.0, 0.0, 1.0, 0.0 };
// the same, as the direction the light travels (fixed-function LightDirection)
float4 LightTravel0 = { -0.8, -0.6, 0.0, 0.0 };
float4 LightTravel1 = { 0.8, -0.6, 0.0, 0.0 };
float4 LightTravel2 = { 0.0, 0.6, -0.8, 0.0 };
float4 LightTravel3 = { 0.0, 0.0, -1.0, 0.0 };

float4 LightRGB0 = { 0.9, 0.2, 0.1, 1.0 };
float4 LightRGB1 = { 0.1, 0.7, 0.2, 1.0 };
float4 LightRGB2 = { 0.2, 0.3, 0.9, 1.0 };
float4 LightRGB3 = { 0.25, 0.25, 0.25, 1.0 };
float4 Ambient     = { 0.05, 0.05, 0.05, 1.0 };

//----------------------------------------------------------------------------------------------

technique MultiLight_ps30
<
    string Description = "SM3: a ps_3_0 loop over four lights, c[aL] directions, c[aL + 4] colours";
    int Quality = 3;
    float Cost = 16.0;
>
{
    pass P0
    {
        VertexShaderConstantF[0] = <WorldViewProjection>;
        VertexShaderConstantF[4] = <World>;
        VertexShader = asm
        {
            vs_3_0
            dcl_position v0
            dcl_normal   v1
            dcl_position o0
            dcl_texcoord0 o1
            m4x4 o0, v0, c0                  // clip position
            m3x3 r0.xyz, v1, c4              // world normal
            mov o1.xyz, r0
        };

        PixelShaderConstantF[0] = <ToLight0>;
        PixelShaderConstantF[1] = <ToLight1>;
        PixelShaderConstantF[2] = <ToLight2>;
        PixelShaderConstantF[3] = <ToLight3>;
        PixelShaderConstantF[4] = <LightRGB0>;
        PixelShaderConstantF[5] = <LightRGB1>;
        PixelShaderConstantF[6] = <LightRGB2>;
        PixelShaderConstantF[7] = <LightRGB3>;
        PixelShaderConstantF[8] = <Ambient>;
        PixelShader = asm
        {
            ps_3_0
            dcl_texcoord0 v0.xyz
            defi i0, 4, 0, 1, 0              // four lights: aL = 0, 1, 2, 3
            nrm r0.xyz, v0                   // N
            mov r1, c8                       // ambient
            loop aL, i0
                dp3_sat r2.x, r0, c[aL]      // sat(N . L)
                mad r1.xyz, c[aL + 4], r2.x, r1
            endloop
            mov oC0, r1
        };
    }
}

technique MultiLight_ps20
<
    string Description = "ps_2_0: the four lights unrolled, per pixel";
    int Quality = 2;
    float Cost = 12.0;
>
{
    pass P0
    {
        VertexShaderConstantF[0] = <WorldViewProjection>;
        VertexShaderConstantF[4] = <World>;
        VertexShader = asm
        {
            vs_1_1
            dcl_position v0
            dcl_normal   v3
            m4x4 oPos, v0, c0
            m3x3 oT0.xyz, v3, c4             // world normal
        };

        PixelShaderConstantF[0] = <ToLight0>;
        PixelShaderConstantF[1] = <ToLight1>;
        PixelShaderConstantF[2] = <ToLight2>;
        PixelShaderConstantF[3] = <ToLight3>;
        PixelShaderConstantF[4] = <LightRGB0>;
        PixelShaderConstantF[5] = <LightRGB1>;
        PixelShaderConstantF[6] = <LightRGB2>;
        PixelShaderConstantF[7] = <LightRGB3>;
        PixelShaderConstantF[8] = <Ambient>;
        PixelShader = asm
        {
            ps_2_0
            dcl t0.xyz
            nrm r0.xyz, t0
            mov r1, c8
            dp3_sat r2.x, r0, c0
            mad r1.xyz, c4, r2.x, r1
            dp3_sat r2.x, r0, c1
            mad r1.xyz, c5, r2.x, r1
            dp3_sat r2.x, r0, c2
            mad r1.xyz, c6, r2.x, r1
            dp3_sat r2.x, r0, c3
            mad r1.xyz, c7, r2.x, r1
            mov oC0, r1
        };
    }
}

technique MultiLight_ff
<
    string Description = "fixed-function vertex lighting, the same four directional lights";
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

        Lighting         = True;
        NormalizeNormals = True;
        Ambient          = <Ambient>;
        MaterialDiffuse  = { 1.0, 1.0, 1.0, 1.0 };
        MaterialAmbient  = { 1.0, 1.0, 1.0, 1.0 };
        MaterialSpecular = { 0.0, 0.0, 0.0, 0.0 };
        MaterialEmissive = { 0.0, 0.0, 0.0, 0.0 };

        LightEnable[0]    = True;
        LightType[0]      = Directional;
        LightDirection[0] = <LightTravel0>;
        LightDiffuse[0]   = <LightRGB0>;
        LightEnable[1]    = True;
        LightType[1]      = Directional;
        LightDirection[1] = <LightTravel1>;
        LightDiffuse[1]   = <LightRGB1>;
        LightEnable[2]    = True;
        LightType[2]      = Directional;
        LightDirection[2] = <LightTravel2>;
        LightDiffuse[2]   = <LightRGB2>;
        LightEnable[3]    = True;
        LightType[3]      = Directional;
        LightDirection[3] = <LightTravel3>;
        LightDiffuse[3]   = <LightRGB3>;

        ColorOp[0]   = SelectArg1;
        ColorArg1[0] = Diffuse;
        AlphaOp[0]   = SelectArg1;
        AlphaArg1[0] = Diffuse;
        ColorOp[1]   = Disable;
        AlphaOp[1]   = Disable;
    }
}
