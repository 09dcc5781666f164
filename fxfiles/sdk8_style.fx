//
// sdk8_style.fx -- a bumpy, reflective teapot written the way DirectX 8.x SDK sample effects
// (and the chapter's BRDF file) were written. It exercises the DX8 effect language: FourCC-like
// 4-letter names (DX8.0 identifiers were FourCC codes), upper-case DWORD / FLOAT / VECTOR /
// MATRIX / TEXTURE / STRING / PIXELSHADER types, `(1.0f, 0.5f, 0.25f, 1.0f)` vector
// initialisers, `<param>` references, `decl {}` vertex declarations before `asm { vs.1.1 }`,
// VertexShaderConstant[n], stage-indexed Texture/ColorOp/MinFilter states, `Texture |
// Complement`, TexCoordIndex with CameraSpaceReflectionVector, an FVF, a named ps.1.4 shader
// referenced as <ps14>, and an anonymous last technique. DX8 files have no annotations or
// semantics: parameters are bound by name (or by the scene's params).
//
// Techniques, best first:
//   TPS4    DX8.1 ps.1.4 (Radeon 8500): dot3 bump in phase 1, base and cube reflection in phase 2
//   TPS1    DX8 ps.1.1 (GeForce3): the same look in 4 texture + 3 arithmetic instructions
//   TFF7    DX7 fixed function (GeForce2): base x vertex light + cube map by
//           CameraSpaceReflectionVector, no bumps
//   TDX6    DX6 fixed function (TNT2, G400): base x vertex light x complement of a dirt map
//   (none)  anything: base x vertex light, one stage
//
// Textures: tBas base (2D), tNrm normal map (2D, biased 0.5*n+0.5), tEnv environment (CUBE),
// tDrt dirt mask (2D, white = dirty). Matrices are loaded transposed for m4x4, as in DX8.
//

// Transforms (set by the application)
MATRIX mWld;            // World
MATRIX mWVP;            // World * View * Projection
MATRIX mViw;            // View
MATRIX mPrj;            // Projection
MATRIX mVIn;            // inverse View: camera-space reflection back to world space

// Light and eye
VECTOR vLgt = (0.577f, -0.577f, -0.577f, 0.0f);   // light direction (the way it travels)
VECTOR vEye = (0.0f, 0.0f, 3.0f, 1.0f);           // eye position, world space
VECTOR cRfl = (1.0f, 0.5f, 0.25f, 1.0f);          // reflectivity: a copper tint
FLOAT  fPow = 16.0f;                              // vertex specular power (fixed function)

TEXTURE tBas;
TEXTURE tNrm;
TEXTURE tEnv;
TEXTURE tDrt;

// For the effect viewer
STRING XFile = "teapot.x";
DWORD  BCLR  = 0xff202040;

// ps.1.4: phase 1 samples the normal map and dots it with the light vector passed in t3;
// phase 2 samples the base and the cube map (r registers keep rgb across `phase`) and
// assembles. c0 = reflectivity.
PIXELSHADER ps14 = asm
{
    ps.1.4
    texld  r1, t1                   // normal map
    texcrd r3.rgb, t3               // light vector, biased into [0,1] by the vertex shader
    dp3_sat r3, r1_bx2, r3_bx2      // N.L

    phase

    texld  r0, t0                   // base texture
    texld  r2, t2                   // environment cube map, reflection vector in t2
    mul    r0.rgb, r0, r3           // base * N.L
    mad    r0.rgb, r2, c0, r0       // + reflection * reflectivity
    +mov   r0.a, c0.a
};

technique TPS4
{
    pass P0
    {
        VertexShaderConstant[0]  = <mWld>;
        VertexShaderConstant[4]  = <mWVP>;
        VertexShaderConstant[12] = <vLgt>;
        VertexShaderConstant[13] = <vEye>;
        VertexShaderConstant[20] = (0.5f, 0.5f, 0.5f, 0.5f);
        PixelShaderConstant[0]   = <cRfl>;

        Texture[0] = <tBas>;
        Texture[1] = <tNrm>;
        Texture[2] = <tEnv>;
        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
        MipFilter[0] = Linear;
        MinFilter[1] = Linear;
        MagFilter[1] = Linear;
        MinFilter[2] = Linear;
        MagFilter[2] = Linear;
        AddressU[2] = Clamp;
        AddressV[2] = Clamp;
        AddressW[2] = Clamp;

        VertexShader =
        decl
        {
            stream 0;
            float v0[3];        // Position
            float v3[3];        // Normal
            float v7[2];        // Texture Coord
            float v8[3];        // Tangent
        }
        asm
        {
            vs.1.1
            // c0-c3 world, c4-c7 world*view*proj, c12 light direction, c13 eye, c20 = .5
            m4x4 oPos, v0, c4          // projection space
            m4x4 r0, v0, c0            // world position
            m3x3 r3.xyz, v8, c0        // tangent to world
            m3x3 r5.xyz, v3, c0        // normal to world

            mul r1.xyz, r5.yzx, r3.zxy // binormal = normal x tangent
            mad r4.xyz, -r5.zxy, r3.yzx, r1

            dp3 r6.x, r3, -c12         // light vector (toward the light) in tangent space
            dp3 r6.y, r4, -c12
            dp3 r6.z, r5, -c12
            mad oD0.xyz, r6.xyz, c20, c20   // for ps.1.1: v0
            mad oT3.xyz, r6.xyz, c20, c20   // for ps.1.4: texcrd t3

            add r7.xyz, c13, -r0       // toward the eye
            dp3 r7.w, r7, r7
            rsq r7.w, r7.w
            mul r7.xyz, r7, r7.w
            dp3 r8.x, r5, r7           // N.E
            add r8.x, r8.x, r8.x       // 2 N.E
            mad oT2.xyz, r5, r8.x, -r7 // reflection vector R = 2(N.E)N - E, world space

            mov oT0.xy, v7             // base
            mov oT1.xy, v7             // normal map
        };

        PixelShader = <ps14>;
    }
}

technique TPS1
{
    pass P0
    {
        VertexShaderConstant[0]  = <mWld>;
        VertexShaderConstant[4]  = <mWVP>;
        VertexShaderConstant[12] = <vLgt>;
        VertexShaderConstant[13] = <vEye>;
        VertexShaderConstant[20] = (0.5f, 0.5f, 0.5f, 0.5f);
        PixelShaderConstant[0]   = <cRfl>;

        Texture[0] = <tBas>;
        Texture[1] = <tNrm>;
        Texture[2] = <tEnv>;
        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
        MipFilter[0] = Linear;
        MinFilter[1] = Linear;
        MagFilter[1] = Linear;
        MinFilter[2] = Linear;
        MagFilter[2] = Linear;
        AddressU[2] = Clamp;
        AddressV[2] = Clamp;
        AddressW[2] = Clamp;

        VertexShader =
        decl
        {
            stream 0;
            float v0[3];
            float v3[3];
            float v7[2];
            float v8[3];
        }
        asm
        {
            vs.1.1
            m4x4 oPos, v0, c4
            m4x4 r0, v0, c0
            m3x3 r3.xyz, v8, c0
            m3x3 r5.xyz, v3, c0
            mul r1.xyz, r5.yzx, r3.zxy
            mad r4.xyz, -r5.zxy, r3.yzx, r1
            dp3 r6.x, r3, -c12
            dp3 r6.y, r4, -c12
            dp3 r6.z, r5, -c12
            mad oD0.xyz, r6.xyz, c20, c20   // light vector in the diffuse colour
            add r7.xyz, c13, -r0
            dp3 r7.w, r7, r7
            rsq r7.w, r7.w
            mul r7.xyz, r7, r7.w
            dp3 r8.x, r5, r7
            add r8.x, r8.x, r8.x
            mad oT2.xyz, r5, r8.x, -r7      // reflection vector
            mov oT0.xy, v7
            mov oT1.xy, v7
        };

        PixelShader =
        asm
        {
            ps.1.1
            tex t0                          // base
            tex t1                          // normal map
            tex t2                          // cube map at the reflection vector

            dp3_sat r1, t1_bx2, v0_bx2      // N.L
            mul r0, t0, r1                  // base * N.L
            mad r0, t2, c0, r0              // + reflection * reflectivity
        };
    }
}

technique TFF7
{
    pass P0
    {
        VertexShader = NULL;
        PixelShader  = NULL;
        FVF = XYZ | Normal | Tex1;

        WorldTransform[0]   = <mWld>;
        ViewTransform       = <mViw>;
        ProjectionTransform = <mPrj>;

        Lighting          = True;
        SpecularEnable    = True;
        LightEnable[0]    = True;
        LightType[0]      = Directional;
        LightDirection[0] = <vLgt>;
        LightDiffuse[0]   = (1.0f, 1.0f, 1.0f, 1.0f);
        LightSpecular[0]  = (0.5f, 0.5f, 0.5f, 1.0f);
        LightAmbient[0]   = (0.1f, 0.1f, 0.1f, 1.0f);
        MaterialDiffuse   = (1.0f, 1.0f, 1.0f, 1.0f);
        MaterialAmbient   = (1.0f, 1.0f, 1.0f, 1.0f);
        MaterialSpecular  = (1.0f, 1.0f, 1.0f, 1.0f);
        MaterialPower     = <fPow>;

        Texture[0]   = <tBas>;
        ColorOp[0]   = Modulate;
        ColorArg1[0] = Texture;
        ColorArg2[0] = Diffuse;
        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
        MipFilter[0] = Linear;

        Texture[1]       = <tEnv>;
        TexCoordIndex[1] = CameraSpaceReflectionVector;
        TextureTransformFlags[1] = Count3;
        TextureTransform[1]      = <mVIn>;
        ColorOp[1]   = Add;
        ColorArg1[1] = Texture;
        ColorArg2[1] = Current;
        AddressU[1]  = Clamp;
        AddressV[1]  = Clamp;
        AddressW[1]  = Clamp;
        MinFilter[1] = Linear;
        MagFilter[1] = Linear;

        ColorOp[2] = Disable;
    }
}

technique TDX6
{
    pass P0
    {
        VertexShader = NULL;
        PixelShader  = NULL;
        FVF = XYZ | Normal | Tex1;

        WorldTransform[0]   = <mWld>;
        ViewTransform       = <mViw>;
        ProjectionTransform = <mPrj>;

        Lighting          = True;
        LightEnable[0]    = True;
        LightType[0]      = Directional;
        LightDirection[0] = <vLgt>;
        LightDiffuse[0]   = (1.0f, 1.0f, 1.0f, 1.0f);
        LightAmbient[0]   = (0.1f, 0.1f, 0.1f, 1.0f);
        MaterialDiffuse   = (1.0f, 1.0f, 1.0f, 1.0f);
        MaterialAmbient   = (1.0f, 1.0f, 1.0f, 1.0f);

        Texture[0]   = <tBas>;
        ColorOp[0]   = Modulate;
        ColorArg1[0] = Texture;
        ColorArg2[0] = Diffuse;
        MinFilter[0] = Linear;
        MagFilter[0] = Linear;

        Texture[1]       = <tDrt>;
        TexCoordIndex[1] = 0;
        ColorOp[1]   = Modulate;
        ColorArg1[1] = Texture | Complement;    // white = dirty, so 1 - dirt = clean
        ColorArg2[1] = Current;
        MinFilter[1] = Linear;
        MagFilter[1] = Linear;

        ColorOp[2] = Disable;
    }
}

// Anything that draws a textured triangle.
technique
{
    pass
    {
        VertexShader = NULL;
        PixelShader  = NULL;
        FVF = XYZ | Normal | Tex1;

        WorldTransform[0]   = <mWld>;
        ViewTransform       = <mViw>;
        ProjectionTransform = <mPrj>;

        Lighting          = True;
        LightEnable[0]    = True;
        LightType[0]      = Directional;
        LightDirection[0] = <vLgt>;
        LightDiffuse[0]   = (1.0f, 1.0f, 1.0f, 1.0f);
        MaterialDiffuse   = (1.0f, 1.0f, 1.0f, 1.0f);

        Texture[0]   = <tBas>;
        ColorOp[0]   = Modulate;
        ColorArg1[0] = Texture;
        ColorArg2[0] = Diffuse;
        ColorOp[1]   = Disable;
    }
}
