// Ours (the effects project), not Wild Magic's: a D3DX technique around Wild Magic 5's
// unmodified LightDirectionalPerPixel.fx (see MANIFEST.md), compiled for vs_2_0/ps_2_0 as Wild Magic's
// own tool compiled it, with the uniform arguments its renderer supplied (wm_host.fxh).
#include "wm_host.fxh"
string VertexStreams = "texcoord1=normal";   // Wild Magic reads the normal from TEXCOORD1
#include "LightDirectionalPerPixel.fx"

technique LightDirectionalPerPixel
{
    pass P0
    {
        VertexShader = compile vs_2_0 v_LightDirectionalPerPixel(PVWMatrix);
        PixelShader = compile ps_2_0 p_LightDirectionalPerPixel(CameraModelPosition, MaterialEmissive, MaterialAmbient, MaterialDiffuse, MaterialSpecular, LightModelDirection, LightAmbient, LightDiffuse, LightSpecular, LightAttenuation);
    }
}
