// Ours (the effects project), not Wild Magic's: a D3DX technique around Wild Magic 5's
// unmodified LightSpotPerPixel.fx (see MANIFEST.md), compiled for vs_2_0/ps_2_0 as Wild Magic's
// own tool compiled it, with the uniform arguments its renderer supplied (wm_host.fxh).
#include "wm_host.fxh"
string VertexStreams = "texcoord1=normal";   // Wild Magic reads the normal from TEXCOORD1
#include "LightSpotPerPixel.fx"

technique LightSpotPerPixel
{
    pass P0
    {
        VertexShader = compile vs_2_0 v_LightSpotPerPixel(PVWMatrix);
        PixelShader = compile ps_2_0 p_LightSpotPerPixel(WMatrix, CameraModelPosition, MaterialEmissive, MaterialAmbient, MaterialDiffuse, MaterialSpecular, LightModelPosition, LightModelDirection, LightAmbient, LightDiffuse, LightSpecular, LightSpotCutoff, LightAttenuation);
    }
}
