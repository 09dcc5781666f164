// Ours (the effects project), not Wild Magic's: a D3DX technique around Wild Magic 5's
// unmodified ScreenShader.fx (see MANIFEST.md), the shader its GPGPU samples (the fluid and
// heat solvers) draw their state texture to the screen with, through a mask, on a
// screen-filling square: p_ScreenShader3 with the boundary colour the samples pass.
#include "wm_host.fxh"
#include "ScreenShader.fx"

float4 BoundaryColor = {0.0, 0.25, 0.5, 1.0};
texture StateTexture;   // stand-ins unless the scene or --set gives them
texture MaskTexture;

technique ScreenShader3
{
    pass P0
    {
        VertexShader = compile vs_2_0 v_ScreenShader(PVWMatrix);
        PixelShader = compile ps_2_0 p_ScreenShader3(BoundaryColor);
        Texture[0] = <StateTexture>;   // in the order the shader uses its samplers
        Texture[1] = <MaskTexture>;
    }
}
