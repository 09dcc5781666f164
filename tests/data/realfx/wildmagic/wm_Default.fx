// Ours (the effects project), not Wild Magic's: a D3DX technique around Wild Magic 5's
// unmodified Default.fx (see MANIFEST.md), compiled for vs_2_0/ps_2_0 as Wild Magic's
// own tool compiled it, with the uniform arguments its renderer supplied (wm_host.fxh).
#include "wm_host.fxh"
#include "Default.fx"

technique Default
{
    pass P0
    {
        VertexShader = compile vs_2_0 v_Default(PVWMatrix);
        PixelShader = compile ps_2_0 p_Default();
    }
}
