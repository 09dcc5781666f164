// Look-alike of a game mod's water effect (written for this project, not copied): ps.1.4
// with a phase, matrix<float,4,3> and vector<float,3> template types, a cast, an ARB
// program left from the mod's OpenGL port (rejected at validation), a backslash-continued
// annotation, and `VertexShader = 0;` resetting to the fixed-function pipeline.

matrix<float, 4, 4> WorldViewProj : WorldViewProjection;
vector<float, 3> WaterTint = {0.2, 0.45, 0.6};
float Time : TIME;
float WaveScale < string UIName = "Wave " \
    "scale"; float UIMin = 0.5; float UIMax = 1.5; >;
texture WaveMap < string Procedural = "sobel_dudv:bumps"; >;
texture SkyMap < string Procedural = "sky_cube:32"; >;

technique WaterARB
{
    pass P0
    {
        PixelShader = asm {
            !!ARBfp1.0
            TEX result.color, fragment.texcoord[0], texture[0], 2D;
            END
        };
    }
}

technique Water14
{
    pass P0
    {
        VertexShader = 0;
        TextureFactor = 0xff3380a0;
        Texture[0] = <WaveMap>;
        Texture[1] = <SkyMap>;
        TexCoordIndex[1] = CameraSpaceReflectionVector;
        TextureTransformFlags[1] = Count3;
        AddressU[0] = Wrap; AddressV[0] = Wrap;
        PixelShader = asm {
            ps.1.4
            texld r0, t0              // the wave (du, dv)
            texcrd r1.xyz, t1         // the reflection vector
            mad r1.xyz, r0, c2, r1    // bent by the wave
            phase
            texld r1, r1              // the sky in the bent direction
            mul r0.rgb, r1, c0        // tinted
            +mov r0.a, c1.a
        };
        PixelShaderConstant[0] = {0.45, 0.75, 1.0, 1.0};
        PixelShaderConstant[1] = (float4)0.9;
        PixelShaderConstant[2] = (float4)0.5;
    }
}

technique WaterFF
{
    pass P0
    {
        Lighting = false;
        TextureFactor = 0xff3380a0;
        Texture[0] = <SkyMap>;
        TexCoordIndex[0] = CameraSpaceReflectionVector;
        TextureTransformFlags[0] = Count3;
        ColorOp[0] = Modulate; ColorArg1[0] = Texture; ColorArg2[0] = TFactor;
        AlphaOp[0] = SelectArg1; AlphaArg1[0] = TFactor;
    }
}
