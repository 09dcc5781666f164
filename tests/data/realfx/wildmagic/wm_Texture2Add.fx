// Ours (the effects project), not Wild Magic's: a D3DX technique around Wild Magic 5's
// unmodified Texture2Add.fx (see MANIFEST.md), compiled for vs_2_0/ps_2_0 as Wild Magic's
// own tool compiled it, with the uniform arguments its renderer supplied (wm_host.fxh).
#include "wm_host.fxh"
#include "Texture2Add.fx"

technique Texture2Add
{
    pass P0
    {
        VertexShader = compile vs_2_0 v_Texture2Add(PVWMatrix);
        PixelShader = compile ps_2_0 p_Texture2Add();
        Texture[0] = <BaseTexture>;   // Wild Magic binds its textures to the samplers in order
        Texture[1] = <SecondTexture>;
    }
}
