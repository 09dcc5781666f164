// Ours (the effects project), not Wild Magic's: a D3DX technique around Wild Magic 5's
// unmodified DLight2MatTex.fx (see MANIFEST.md), compiled for vs_2_0/ps_2_0 as Wild Magic's
// own tool compiled it, with the uniform arguments its renderer supplied (wm_host.fxh).
#include "wm_host.fxh"
string VertexStreams = "texcoord1=normal";   // Wild Magic reads the normal from TEXCOORD1
#include "DLight2MatTex.fx"

technique DLight2MatTex
{
    pass P0
    {
        VertexShader = compile vs_2_0 v_DLight2MatTex(PVWMatrix, CameraModelPosition, MaterialEmissive, MaterialAmbient, MaterialDiffuse, MaterialSpecular, Light0ModelDirection, LightAmbient, LightDiffuse, LightSpecular, LightAttenuation, Light1ModelDirection, LightAmbient, Light1Diffuse, LightSpecular, LightAttenuation);
        PixelShader = compile ps_2_0 p_DLight2MatTex();
        Texture[0] = <BaseTexture>;   // Wild Magic binds its textures to the samplers in order
    }
}
