// Ours (the effects project), not Wild Magic's: a D3DX technique around Wild Magic 5's
// unmodified MaterialTexture.fx (see MANIFEST.md), compiled for vs_2_0/ps_2_0 as Wild Magic's
// own tool compiled it, with the uniform arguments its renderer supplied (wm_host.fxh).
#include "wm_host.fxh"
#include "MaterialTexture.fx"

technique MaterialTexture
{
    pass P0
    {
        VertexShader = compile vs_2_0 v_MaterialTexture(PVWMatrix, MaterialDiffuse);
        PixelShader = compile ps_2_0 p_MaterialTexture();
        Texture[0] = <BaseTexture>;   // Wild Magic binds its textures to the samplers in order
    }
}
