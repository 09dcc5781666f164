// Ours (the effects project), not Allegro's: the effect Allegro 5's Direct3D shader path
// (src/win/d3d_shader.c) builds from its example ex_shader's unmodified vertex and pixel
// sources (see MANIFEST.md): both sources, then a technique TECH with one pass p1 compiling
// vs_main for vs_2_0 and ps_main for ps_2_0. Allegro sets al_projview_matrix (bound here by
// that name, see the README) and al_tex (the bitmap drawn: data/mysha.pcx in the example,
// a stand-in unless --set gives it); the example sets tint by name, e.g. (4, 0, 1).
// Allegro's vertices carry their colour in TEXCOORD1.
string VertexStreams = "texcoord1=diffuse";
#include "ex_shader_vertex.hlsl"
#include "ex_shader_pixel.hlsl"

technique TECH
{
    pass p1
    {
        VertexShader = compile vs_2_0 vs_main();
        PixelShader = compile ps_2_0 ps_main();
    }
}
