// hemisphere.fx -- the "DIY" hemisphere lighting of Philip Taylor's "Per-Pixel Lighting" (in
// Chas Boyd, "Hardware Shading with Direct3D", chapter 5): two far-field colours, sky and
// ground, mixed by a = 0.5 + 0.5*cos(angle between the normal and the sky axis), darkened by
// an occlusion term. Techniques in fallback order:
//
//   HemisphereOcclusion_ps11 DX8 (GeForce3, Radeon 8500): the chapter's three-term model per
//                            pixel: the per-pixel fragment corrected (a reaches 0 below the
//                            equator), times the vertex occlusion and the normal map's alpha
//   HemispherePerPixel_ps11  DX8: the chapter's per-pixel fragment as printed (named only: it
//                            comes after the corrected one, which every ps.1.1 card runs)
//   HemisphereVertex_vs11    DX7 and DX6 (GeForce2, G400, TNT2 with software vertex
//                            processing): the chapter's vs.1.1 listing, colour in oD0, one
//                            MODULATE stage with the base texture ("This will work even on
//                            DirectX 7-class hardware")
//   SingleTexture            anything: fixed function, ground colour as ambient, sky colour
//                            as a directional light shining down the sky axis
//
// Technique annotations: `int Quality` (higher looks better) and `float Cost` (texture reads
// + arithmetic slots or texture stages per pixel); texture annotations as in
// fxfiles/README.md. The occlusion term is texcoord0.z (0 = open, 1 = fully occluded), as the
// chapter's shaders read it (v7.z): VertexStreams below asks the host for the mesh's
// uv_occlusion attribute, (u, v, occlusion), cast once per mesh over its own triangles
// ("firing a hemisphere of rays from each normal", effects/assets/occlusion.py); inline
// vertices get 0. The pixel-to-pixel occlusion of the relief ("firing rays in a height field
// and storing the result in the alpha channel of a normal map") is the normal map's alpha.
// Constants follow the chapter: c0-c3 world, c8-c11 world*view*projection, c33 = .5,
// c40 sky vector, c41 sky colour, c42 ground colour, c43 material colour, c44 = (1,1,1,1).

//----------------------------------------------------------------------------------------------
// Parameters

// texcoord0 = (u, v, vertex occlusion), the chapter's v7 (fxfiles/README.md, Vertex streams).
string VertexStreams = "texcoord0=uv_occlusion";

float4x4 World               : WORLD;
float4x4 View                : VIEW;
float4x4 Projection          : PROJECTION;
float4x4 WorldViewProjection : WORLDVIEWPROJECTION;

float4 SkyVector
<
    string UIName = "Hemisphere axis (world space, unit, toward the sky)";
> = { 0.0, 1.0, 0.0, 0.0 };

float4 SkyColor    < string UIWidget = "Color"; > = { 0.55, 0.65, 0.90, 1.0 };
float4 GroundColor < string UIWidget = "Color"; > = { 0.30, 0.22, 0.15, 1.0 };
float4 MaterialColor < string UIWidget = "Color"; > = { 1.0, 1.0, 1.0, 1.0 };

// The fixed-function fallback's light: the way the sky light travels, i.e. -SkyVector.
float4 SkyLightDirection = { 0.0, -1.0, 0.0, 0.0 };

texture BaseTexture
<
    string ResourceName = "textures/stones_base.png";
    string Type = "2D";
>;

// rgb = the Sobel normal, alpha = 1 - the height field's occlusion of itself.
texture NormalMap
<
    string Procedural = "sobel_normals_ao:textures/stones_height.png";
    string Type = "2D";
    string Format = "A8R8G8B8";
    int Width = 128;
    int Height = 128;
>;

// The chapter's "standard tangent space basis vertex shader" with the hemisphere axis in place
// of the light direction, for both per-pixel techniques.
VertexShader HemisphereVS = asm
{
    vs_1_1
    dcl_position  v0
    dcl_normal    v3
    dcl_texcoord0 v7
    dcl_tangent   v8

    m4x4 oPos, v0, c8                // transform position

    //tangent space basis generation
    m3x3 r3.xyz, v8, c0              // transform tan to world space
    m3x3 r5.xyz, v3, c0              // transform norm to world space
    mul  r0.xyz, r5.yzx, r3.zxy
    mad  r4.xyz, -r5.zxy, r3.yzx, r0 // binormal = normal x tangent

    dp3 r6.x, r3, c40                // transform the hemisphere axis
    dp3 r6.y, r4, c40                // by the resulting matrix
    dp3 r6.z, r5, c40                // r6 is the axis in tangent space

    mad oD0.xyz, r6.xyz, c33, c33    // biased for _bx2
    sub oD0.w, c44.w, v7.z           // 1 - occlusion

    mov oT0.xy, v7                   // normal map
    mov oT1.xy, v7                   // base texture
};

//----------------------------------------------------------------------------------------------
// Techniques, best first

// DX8: the three-term model per pixel. The printed fragment (next technique) with two
// changes: `dp3_d2` without `_sat` (the printed `_sat` clamps N.A / 2 at 0, so the lower
// half of the object stays at the 50/50 mix instead of reaching the ground colour that
// a = 0.5 + 0.5 cos(angle) gives there and the vertex technique draws), and the occlusion
// its comment announces but never applies: v0.a = 1 - vertex occlusion, t0.a = 1 - the
// relief's occlusion. ps.1.1 holds values in [-1, 1], so N.A / 2 fits.
technique HemisphereOcclusion_ps11
<
    string Description = "ps.1.1 per-pixel hemisphere lighting, vertex and relief occlusion (three terms)";
    int Quality = 4;
    float Cost = 8.0;
>
{
    pass P0
    {
        VertexShaderConstantF[0]  = <World>;
        VertexShaderConstantF[8]  = <WorldViewProjection>;
        VertexShaderConstantF[33] = { 0.5, 0.5, 0.5, 0.5 };
        VertexShaderConstantF[40] = <SkyVector>;
        VertexShaderConstantF[44] = { 1.0, 1.0, 1.0, 1.0 };

        VertexShader = <HemisphereVS>;

        Texture[0] = <NormalMap>;
        Texture[1] = <BaseTexture>;
        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
        MinFilter[1] = Linear;
        MagFilter[1] = Linear;
        MipFilter[1] = Linear;

        PixelShaderConstantF[1] = <SkyColor>;
        PixelShaderConstantF[2] = <GroundColor>;
        PixelShaderConstantF[5] = { 0.5, 0.5, 0.5, 0.5 };

        PixelShader = asm
        {
            ps.1.1
            tex t0                           // normal map; alpha = 1 - relief occlusion
            tex t1                           // base texture

            dp3_d2 r0, v0_bx2, t0_bx2        // N.A / 2 (changed: no _sat)
            add r0, r0, c5                   // a = 0.5 + 0.5 N.A
            lrp r0, r0, c1, c2               // a sky + (1 - a) ground
            mul r0, r0, t1                   // modulate base texture
            mul r0, r0, v0.a                 // added: * (1 - vertex occlusion)
            mul r0, r0, t0.a                 // added: * (1 - relief occlusion)
        };
    }
}

// DX8: the chapter's per-pixel fragment as printed (named only). It is printed without its
// version line; `ps.1.1` was added. Its `dp3_d2_sat` keeps the lower half of the object at
// the 50/50 mix, and it leaves v0.a (the occlusion) unused. v0.rgb = hemisphere axis in
// tangent space (biased), v0.a = 1 - occlusion; c1 = sky colour, c2 = ground colour, c5 = .5.
technique HemispherePerPixel_ps11
<
    string Description = "ps.1.1 per-pixel hemisphere lighting with a normal map";
    int Quality = 3;
    float Cost = 6.0;
>
{
    pass P0
    {
        VertexShaderConstantF[0]  = <World>;
        VertexShaderConstantF[8]  = <WorldViewProjection>;
        VertexShaderConstantF[33] = { 0.5, 0.5, 0.5, 0.5 };
        VertexShaderConstantF[40] = <SkyVector>;
        VertexShaderConstantF[44] = { 1.0, 1.0, 1.0, 1.0 };

        VertexShader = <HemisphereVS>;

        Texture[0] = <NormalMap>;
        Texture[1] = <BaseTexture>;
        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
        MinFilter[1] = Linear;
        MagFilter[1] = Linear;
        MipFilter[1] = Linear;

        PixelShaderConstantF[1] = <SkyColor>;
        PixelShaderConstantF[2] = <GroundColor>;
        PixelShaderConstantF[5] = { 0.5, 0.5, 0.5, 0.5 };

        PixelShader = asm
        {
            ps.1.1                           // added: the chapter prints no version line
            //   v0.rgb is hemi axis in tangent space
            // v0.a is occlusion ratio from vshader
            tex t0                           // normal map
            tex t1                           // base texture

            dp3_d2_sat r0,v0_bx2,t0_bx2      // dot normal with hemi axis
            add r0,r0,c5                     // map into range, not _sat
            lrp r0,r0,c1,c2
            mul r0,r0,t1                     // modulate base texture
        };
    }
}

// The chapter's vertex hemisphere shader. Changes, all marked: the DX9 `dcl_` lines (DX9
// assembly declares its inputs; the chapter's DX8 code had a decl block instead), the .xyz
// mask m3x3 requires in DX9, and `mov oT0.xy, v7` so stage 0 can apply the base texture.
technique HemisphereVertex_vs11
<
    string Description = "vs.1.1 hemisphere lighting per vertex, one MODULATE stage";
    int Quality = 2;
    float Cost = 1.0;
>
{
    pass P0
    {
        VertexShaderConstantF[0]  = <World>;
        VertexShaderConstantF[8]  = <WorldViewProjection>;
        VertexShaderConstantF[33] = { 0.5, 0.5, 0.5, 0.5 };
        VertexShaderConstantF[40] = <SkyVector>;
        VertexShaderConstantF[41] = <SkyColor>;
        VertexShaderConstantF[42] = <GroundColor>;
        VertexShaderConstantF[43] = <MaterialColor>;
        VertexShaderConstantF[44] = { 1.0, 1.0, 1.0, 1.0 };

        VertexShader = asm
        {
            vs.1.1         // vertex hemisphere shader
            dcl_position  v0                 // added: DX9 input declarations
            dcl_normal    v3
            dcl_texcoord0 v7

            m4x4 oPos,v0,c8   // transform position
            m3x3 r0.xyz, v3,c0   // transform normal (added: .xyz mask)

            dp3 r0,r0,c40   // c40 is sky vector
            mov r1,c33      // c33 is .5f in all channels
            mad r0,r0,c33,r1   // bias operation

            mov r1,c42      // c42 is ground color
            sub r1,c41,r1      // c41 is sky color
            mad r0,r1,r0,c42   // lerp operation

            //c44 = (1,1,1,1)
            sub r1,c44,v7.zzz   // v7.zzz = occlusion term
            mul r0,r0,r1
            mul oD0,r0,c43

            mov oT0.xy, v7.xy   // added: base texture coordinates
        };
        PixelShader = NULL;

        Texture[0]   = <BaseTexture>;
        ColorOp[0]   = Modulate;
        ColorArg1[0] = Texture;
        ColorArg2[0] = Diffuse;
        AlphaOp[0]   = SelectArg1;
        AlphaArg1[0] = Diffuse;
        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
        MipFilter[0] = Linear;
        ColorOp[1]   = Disable;
    }
}

// Anything: fixed-function approximation. Ambient = ground colour everywhere, plus the sky
// colour as a directional light down the sky axis (the FF pipeline clamps N.L at zero, so the
// lower hemisphere gets the ground colour alone).
technique SingleTexture
<
    string Description = "fixed function: ground colour ambient + sky colour directional light";
    int Quality = 1;
    float Cost = 1.0;
>
{
    pass P0
    {
        VertexShader = NULL;
        PixelShader  = NULL;
        WorldTransform[0]   = <World>;
        ViewTransform       = <View>;
        ProjectionTransform = <Projection>;

        Lighting          = True;
        LightEnable[0]    = True;
        LightType[0]      = Directional;
        LightDirection[0] = <SkyLightDirection>;
        LightDiffuse[0]   = <SkyColor>;
        LightAmbient[0]   = <GroundColor>;
        MaterialDiffuse   = <MaterialColor>;
        MaterialAmbient   = <MaterialColor>;

        Texture[0]   = <BaseTexture>;
        ColorOp[0]   = Modulate;
        ColorArg1[0] = Texture;
        ColorArg2[0] = Diffuse;
        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
        MipFilter[0] = Linear;
        ColorOp[1]   = Disable;
    }
}
