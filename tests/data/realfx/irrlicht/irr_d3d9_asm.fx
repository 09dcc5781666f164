// Ours (the effects project), not Irrlicht's: D3DX techniques around Irrlicht 1.8's unmodified
// example shaders d3d9.vsh and d3d9.psh (see MANIFEST.md), included into
// asm blocks, with the constants its example 10.Shaders sets in OnSetConstants:
//   c0-c3   the inverse world matrix     c4-c7   world * view * projection
//   c8      the light position (the camera's, in the example)
//   c9      the light colour (0, 1, 1, 0)  c10-c13 the transposed world matrix
// Irrlicht copies its matrices' rows into the registers; an effect's matrix parameter goes in
// by columns, so each parameter below is the transpose of what Irrlicht's pointer held.
float4x4 mInvWorld : WORLDINVERSETRANSPOSE;
float4x4 mWorldViewProj : WORLDVIEWPROJECTIONTRANSPOSE;
float4x4 mTransWorld : WORLD;
float4 mLightPos : CAMERAPOSITION;
float4 mLightColor = {0.0, 1.0, 1.0, 0.0};

// The example's material: wall.bmp (here the wall.jpg Irrlicht ships) on a sphere
texture wall < string ResourceName = "wall.jpg"; >;

technique Irrlicht_vs11_ps11_dx9
{
    pass P0
    {
        VertexShaderConstant4[0] = <mInvWorld>;
        VertexShaderConstant4[4] = <mWorldViewProj>;
        VertexShaderConstant1[8] = <mLightPos>;
        VertexShaderConstant1[9] = <mLightColor>;
        VertexShaderConstant4[10] = <mTransWorld>;
        Texture[0] = <wall>;
        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
        VertexShader = asm {
#include "d3d9.vsh"
        };
        PixelShader = asm {
#include "d3d9.psh"
        };
    }
}

// What the example does when the card has no shaders: the plain textured material
// (EMT_SOLID, unlit)
technique Irrlicht_Solid
{
    pass P0
    {
        Lighting = false;
        Texture[0] = <wall>;
        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
        ColorOp[0] = SelectArg1;
        ColorArg1[0] = Texture;
    }
}
