// Look-alike of a DirectX 9 SDK EffectEdit sample (written for this project, not copied):
// upper-case SAS semantics, an XFile annotation, a cube map named by a file that is not
// shipped, and a DX7-class fixed-function technique that leaves the transforms to the
// application (EffectEdit sets WORLD/VIEW/PROJECTION from its camera).

string XFile = "sphere.x";
float4x4 matWorld : WORLD, matView : VIEW;
float4x4 matWorldViewProj : WORLDVIEWPROJECTION : register(c0);
float4 vMaterial : DIFFUSE = {0.9f, 0.9f, 1.0f, 1.0f};

textureCUBE tEnvMap < string ResourceName = "lobbycube.dds"; string type = "CUBE"; >;

technique TEnvMapFF
{
    pass P0
    {
        Lighting = false;
        TextureFactor = 0xffe0e0ff;
        Texture[0] = <tEnvMap>;
        TexCoordIndex[0] = CameraSpaceReflectionVector;
        TextureTransformFlags[0] = Count3;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        ColorOp[0] = Modulate; ColorArg1[0] = Texture; ColorArg2[0] = TFactor;
        AlphaOp[0] = SelectArg1; AlphaArg1[0] = TFactor;
        ColorOp[1] = Disable; AlphaOp[1] = Disable;
        PixelShader = 0;
        VertexShader = 0;
    }
}
