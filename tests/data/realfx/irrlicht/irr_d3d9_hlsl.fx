// Ours (the effects project), not Irrlicht's: a D3DX technique around Irrlicht 1.8's
// unmodified example shader d3d9.hlsl (see MANIFEST.md). Its example 10.Shaders compiles
// vertexMain for vs_1_1 and pixelMain for ps_1_1 (EVST_VS_1_1, EPST_PS_1_1) and sets the
// globals by name every frame: mWorldViewProj, mInvWorld (the inverse world), mTransWorld
// (the transposed world), mLightPos (the camera's position) and mLightColor (0, 1, 1, 0).
// The file declares them without semantics, so a host binds them by name (the XNA
// convention, see the README); the colour and the light at the camera are the example's
// choice and come from --set / scene params (tests/test_realfx_debian.py sets them).
// The material's texture goes to stage 0, where the compiled shader's sampler is.
#include "d3d9.hlsl"

texture wall < string ResourceName = "wall.jpg"; >;

technique Irrlicht_HLSL
{
    pass P0
    {
        VertexShader = compile vs_1_1 vertexMain();
        PixelShader = compile ps_1_1 pixelMain();
        Texture[0] = <wall>;
        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
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
