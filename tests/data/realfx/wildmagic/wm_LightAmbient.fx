// Ours (the effects project), not Wild Magic's: a D3DX technique around Wild Magic 5's
// unmodified LightAmbient.fx (see MANIFEST.md), compiled for vs_2_0/ps_2_0 as Wild Magic's
// own tool compiled it, with the uniform arguments its renderer supplied (wm_host.fxh).
#include "wm_host.fxh"
#include "LightAmbient.fx"

technique LightAmbient
{
    pass P0
    {
        VertexShader = compile vs_2_0 v_LightAmbient(PVWMatrix, MaterialEmissive, MaterialAmbient, LightAmbient, LightAttenuation);
        PixelShader = compile ps_2_0 p_LightAmbient();
    }
}
