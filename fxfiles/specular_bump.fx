// specular_bump.fx -- the bump-mapped, specular Earth of Chas Boyd, "Hardware Shading with
// Direct3D" (chapter 5) and Philip Taylor's "Per-Pixel Lighting" that follows it: one logical
// look (a lit Earth whose relief catches a highlight), one technique per hardware generation.
// Techniques in fallback order (the first valid one is used):
//
//   Specular_ps20          DX9  (Radeon 9700): per-pixel Blinn specular with a true exponent
//                          (pow) and per-pixel normalised vectors, no banding
//   SpecularTable_ps11     DX8  (GeForce3, Radeon 8500): the chapter's texm3x2pad/texm3x2tex
//                          dependent read into a power-table texture (u = N.L, v = N.H)
//   SpecularMultiply_ps11  DX8: the chapter's exponent by repeated multiplies (^16); 8-bit
//                          products band in the highlight (the chapter's Figure 5)
//   Dot3_dx7               DX7  (GeForce2): the chapter's DOTPRODUCT3 stages, light vector in
//                          the diffuse colour; diffuse relief only
//   BumpEnvMap_dx6         DX6  (Matrox G400): the chapter's DirectX 6 listing: MODULATE base
//                          by diffuse, BUMPENVMAP a V8U8 bump map, ADD the environment map
//   Emboss_dx6             DX6  (TNT2, Voodoo3): the chapter's emboss (height map minus the
//                          height map shifted toward the light, ADDSIGNED with COMPLEMENT), then
//                          a second pass that multiplies in the lit Earth (2x, to brighten)
//   SingleTexture          anything: fixed-function vertex lighting times the Earth texture
//
// Technique annotations (fxfiles/README.md): `int Quality` -- higher looks better, comparable
// inside this file; `float Cost` -- texture reads + arithmetic instruction slots (or active
// texture stages) per pixel, summed over passes.
// Texture annotations: `string ResourceName` (a file relative to this one) or
// `string Procedural = "generator:argument"` (made at load time), with `Type`, `Format`,
// `Width`, `Height` where they matter (fxfiles/README.md lists the generators).
//
// Vertex layout, as the chapter's BUMPVERTEX: texcoord set 1 holds the surface (Earth)
// coordinates, set 0 the environment-map coordinates the DirectX 6 technique looks up
// (TEXCOORDINDEX 1, 1, 0 in the listing). Shaders also read the normal and the tangent.
// Vertex shader constants follow the chapter's render-state lists: c0-c3 world,
// c8-c11 world*view*projection (the "total matrix"), c12 light direction, c14 camera position,
// c20 = (.5,.5,.5,.5), c24 emboss offset. (The chapter's code fragments use other numbers
// -- c4, c16, c24 -- than its state lists; this file uses the state lists throughout.)
// Matrices are read by m4x4/m3x3 as rows of the transpose ("World Matrix (transpose)").
// The light is directional (the Sun): LightDirection is the way the light travels, as in
// D3DLIGHT9, so the shaders use -c12 as the vector toward the light.

//----------------------------------------------------------------------------------------------
// Parameters

float4x4 World               : WORLD;
float4x4 View                : VIEW;
float4x4 Projection          : PROJECTION;
float4x4 WorldViewProjection : WORLDVIEWPROJECTION;

float4 LightDirection : LIGHTDIRECTION
<
    string UIName = "Sun direction (world space, the way the light travels)";
    string Space = "World";
> = { 0.577, -0.577, -0.577, 0.0 };

float4 LightColor : LIGHTCOLOR
<
    string UIWidget = "Color";
> = { 1.0, 1.0, 1.0, 1.0 };

float4 CameraPosition : CAMERAPOSITION = { 0.0, 0.0, 3.0, 1.0 };

float4 SpecularColor
<
    string UIName = "Specular colour";
    string UIWidget = "Color";
> = { 0.6, 0.6, 0.6, 1.0 };

// 16: the chapter's multiply technique stops there ("don't try to use the technique for
// powers greater than 16"); the ps_2_0 and table techniques use the same value so the three
// highlights can be compared.
float SpecularPower
<
    string UIName = "Specular exponent";
    float UIMin = 1.0;
    float UIMax = 128.0;
> = 16.0;

// Emboss: how far (in texture coordinates) the height map is shifted toward the light:
// two texels of the 128x128 height map. Measured against the Dot3 technique's relief (the
// mean change real bumps make over the sunlit side, Earth colour on): one texel (0.008)
// draws 0.21 of it, two 0.41 (3.3 against 8.0 levels), following its sign (correlation
// 0.85); four would draw 0.75 but follow it less (0.71), the shift outrunning the bumps it
// should outline (tests/looks/test_seed_looks.py). The chapter sets no target: the results
// "can take quite an effort to fine tune".
float4 EmbossOffset = { 0.016, 0.016, 0.0, 0.0 };

texture EarthTexture
<
    string ResourceName = "textures/earth_base.png";
    string Type = "2D";
>;

// No Format annotation: the emboss technique works with whatever RGB format the card has
// (the DX6 cards list no L8; the Voodoo3 only 16-bit formats), as the chapter's emboss needs
// only two texture units and a subtract.
texture HeightMap
<
    string ResourceName = "textures/earth_height.png";
    string Type = "2D";
>;

texture NormalMap
<
    string Procedural = "sobel_normals:textures/earth_height.png";
    string Type = "2D";
    string Format = "X8R8G8B8";
    int Width = 128;
    int Height = 128;
>;

// The DirectX 6 bump map: signed (du, dv) per texel.
texture BumpMap
<
    string Procedural = "sobel_dudv:textures/earth_height.png";
    string Type = "2D";
    string Format = "V8U8";
    int Width = 128;
    int Height = 128;
>;

// The environment map of the DirectX 6 technique: a light map holding the highlight.
texture EnvMapTexture
<
    string ResourceName = "textures/earth_light.png";
    string Type = "2D";
>;

// The table of the chapter's LightEval: rgb = pow(v, SpecularPower), alpha = u, made again
// whenever SpecularPower changes (as their D3DXFillTexture(LightEval, &fPower) would be
// called again). 256 rows as in the chapter: N.H = 1 reads the last row's centre, so the
// table's peak is (1 - 0.5/256)^SpecularPower, 0.82 at 100.
texture PowerTable
<
    string Procedural = "power_table:<SpecularPower>";
    string Type = "2D";
    string Format = "A8R8G8B8";
    int Width = 256;
    int Height = 256;
>;

sampler2D EarthSampler = sampler_state
{
    Texture = <EarthTexture>;
    MinFilter = Linear;
    MagFilter = Linear;
    MipFilter = Linear;
};

sampler2D NormalSampler = sampler_state
{
    Texture = <NormalMap>;
    MinFilter = Linear;
    MagFilter = Linear;
    MipFilter = Linear;
};

//----------------------------------------------------------------------------------------------
// Vertex shaders

// Tangent-space light vector and half angle, passed as texture coordinates (not clamped):
// oT0 = surface coordinates (normal map), oT1 = light vector, oT2 = half angle,
// oT3 = surface coordinates again (colour map of the table technique).
// The half-angle code is the chapter's (with write masks and its register numbers mapped to
// the state lists); the chapter's table shader passed the half angle in both oT1 and oT2,
// its text says stage 1 carries the light direction, which this shader does.
VertexShader EarthVS_vectors = asm
{
    vs_1_1
    dcl_position  v0
    dcl_normal    v3
    dcl_texcoord1 v7                // surface coordinates (set 1)
    dcl_tangent   v8

    //transform position
    m4x4 oPos, v0, c8

    //tsb generation
    m3x3 r3.xyz, v8, c0             //tangent to world space
    m3x3 r5.xyz, v3, c0             //normal to world space
    mul  r0.xyz, r5.yzx, r3.zxy
    mad  r4.xyz, -r5.zxy, r3.yzx, r0 //binormal = normal x tangent

    //light vector in tangent space
    dp3 r6.x, r3, -c12
    dp3 r6.y, r4, -c12
    dp3 r6.z, r5, -c12

    //specular
    m4x4 r2, v0, c0                 //transform position
    add r2, -r2, c14                //get a vector toward the camera
    dp3 r11.x, r2.xyz, r2.xyz       //load the square into r11
    rsq r11.x, r11.x                //get the inverse of the square
    mul r2.xyz, r2.xyz, r11.x       //r2 = camera vector
    add r2.xyz, r2.xyz, -c12        //get half angle

    //normalize
    dp3 r11.x, r2.xyz, r2.xyz
    rsq r11.x, r11.x
    mul r2.xyz, r2.xyz, r11.x       //r2 = HalfAngle

    //transform the half angle vector
    dp3 r8.x, r3, r2
    dp3 r8.y, r4, r2
    dp3 r8.z, r5, r2

    //tex coords
    mov oT0.xy, v7                  //coord to sample normal from
    mov oT1.xyz, r6                 //not a tex coord: light direction
    mov oT2.xyz, r8                 //not a tex coord: half angle
    mov oT3.xy, v7                  //colour map
};

// The chapter's diffuse/specular setup for colour interpolators: the light vector in oD0 and
// the half angle in oD1, each multiplied by a half and offset by a half for _bx2;
// oT0 = oT1 = surface coordinates. Also the DX7 DOTPRODUCT3 path (which reads oD0 only);
// DX7 cards run it by software vertex processing, as the chapter's fallback does.
VertexShader EarthVS_colors = asm
{
    vs_1_1
    dcl_position  v0
    dcl_normal    v3
    dcl_texcoord1 v7
    dcl_tangent   v8
    def c20, 0.5, 0.5, 0.5, 0.5

    m4x4 oPos, v0, c8

    m3x3 r3.xyz, v8, c0
    m3x3 r5.xyz, v3, c0
    mul  r0.xyz, r5.yzx, r3.zxy
    mad  r4.xyz, -r5.zxy, r3.yzx, r0

    //diffuse, transform the light vector
    dp3 r6.x, r3, -c12
    dp3 r6.y, r4, -c12
    dp3 r6.z, r5, -c12

    //light in oD0
    mad oD0.xyz, r6.xyz, c20, c20   //multiply by a half then add half
    mov oD0.w, c20.w

    m4x4 r2, v0, c0
    add r2, -r2, c14
    dp3 r11.x, r2.xyz, r2.xyz
    rsq r11.x, r11.x
    mul r2.xyz, r2.xyz, r11.x
    add r2.xyz, r2.xyz, -c12
    dp3 r11.x, r2.xyz, r2.xyz
    rsq r11.x, r11.x
    mul r2.xyz, r2.xyz, r11.x

    dp3 r8.x, r3, r2
    dp3 r8.y, r4, r2
    dp3 r8.z, r5, r2

    //half-angle in oD1
    mad oD1.xyz, r8.xyz, c20, c20   //multiply by a half, add half
    mov oD1.w, c20.w

    //tex coords
    mov oT0.xy, v7
    mov oT1.xy, v7
};

// The chapter's emboss vertex shader: shift the height map's coordinates by the tangent-space
// light direction (x and y only), and put N.L in oD0 for the global darkening.
VertexShader EarthVS_emboss = asm
{
    vs_1_1                          // for emboss
    dcl_position  v0
    dcl_normal    v3
    dcl_texcoord1 v7
    dcl_tangent   v8

    m4x4 oPos, v0, c8               // generate output position

    //diffuse
    m3x3 r3.xyz, v8, c0             // transform tan to world space
    m3x3 r5.xyz, v3, c0             // transform norm to world space
    mul  r0.xyz, r5.yzx, r3.zxy
    mad  r4.xyz, -r5.zxy, r3.yzx, r0 // binormal = normal x tangent

    dp3 r6.x, r3, -c12              // tangent space light in r6
    dp3 r6.y, r4, -c12
    //  dp3 r6.z, r5, -c12  don't need this
    //                      -only x and y shifts matter

    // set up the texture, based on light direction:
    mul r1.xy, r6.xy, c24.xy
    mov oT0.xy, v7                  // copy the base height map
    add oT1.xy, v7, r1.xy           // offset the normal height map

    // simple dot product to get global darkening effects:
    dp3 oD0.xyz, r5, -c12
    mov oD0.w, c20.w                // c20 = (.5,.5,.5,.5) from the pass; alpha unused
};

// The DirectX 6 technique's vertices, as the SDK's BumpEarth application made them on the CPU:
// the Earth lit per vertex (oD0 = max(0, N.L) * light colour, what the listing's lit FVF
// vertices carry) and view-dependent environment coordinates (oT2), so the light map's spot,
// the Sun's reflection, lands where the surface mirrors the Sun to the eye: one coherent
// highlight instead of the surface uv's scattered copies. The coordinates measure the normal
// against the vertex's half angle H of the Sun and the eye:
//     (u, v) = 0.5 + k (N.a, N.b),   a = normalize(H x up), b = a x H
// so (0.5, 0.5) (the spot) is N = H and the spot's width is the angle to it; k = 0.32 gives
// the light map's Gaussian (sigma 0.08) the width of N.H^16 (exp(-8 angle^2)). DX6 cards
// run it by software vertex processing, as the other vs.1.1 fallbacks here.
VertexShader EarthVS_envmap = asm
{
    vs_1_1
    dcl_position  v0
    dcl_normal    v3
    dcl_texcoord1 v7                // surface coordinates (set 1)

    // c0-c3 world, c8-c11 world*view*projection, c12 light direction, c14 camera position,
    // c16 light colour; c21 = (k, 0, 0, 0)
    def c21, 0.32, 0.0, 0.0, 0.0
    def c20, 0.5, 0.5, 0.5, 0.5

    m4x4 oPos, v0, c8
    m3x3 r5.xyz, v3, c0             // normal, world space
    dp3 r0.w, r5, r5
    rsq r0.w, r0.w
    mul r5.xyz, r5, r0.w

    dp3 r1.x, r5, -c12              // N.L
    max r1.x, r1.x, c21.y
    mul oD0, c16, r1.x              // lit Earth colour, as the FVF vertex's diffuse

    // H: the half angle of the Sun and the eye at this vertex
    m4x4 r0, v0, c0                 // world position
    sub r2.xyz, c14, r0             // toward the eye
    dp3 r2.w, r2, r2
    rsq r2.w, r2.w
    mul r2.xyz, r2, r2.w
    sub r2.xyz, r2, c12             // + direction to the Sun
    dp3 r2.w, r2, r2
    rsq r2.w, r2.w
    mul r2.xyz, r2, r2.w            // r2 = H

    mov r3.x, -r2.z                 // a = H x (0, 1, 0) = (-H.z, 0, H.x)
    mov r3.y, c21.y
    mov r3.z, r2.x
    dp3 r3.w, r3, r3
    rsq r3.w, r3.w
    mul r3.xyz, r3, r3.w            // a
    mul r4.xyz, r3.yzx, r2.zxy
    mad r4.xyz, r3.zxy, r2.yzx, -r4 // b = a x H

    dp3 r6.x, r5, r3
    dp3 r6.y, r5, r4
    mul r6.xy, r6.xy, c21.x
    add oT2.xy, r6.xy, c20          // 0.5 + k (N.a, N.b)

    mov oT0.xy, v7                  // Earth
    mov oT1.xy, v7                  // bump map
};

//----------------------------------------------------------------------------------------------
// Techniques, best first

// DX9: per-pixel Blinn specular with a real pow: no banding at any exponent.
technique Specular_ps20
<
    string Description = "ps_2_0 per-pixel diffuse + specular, true exponent";
    int Quality = 7;
    float Cost = 20.0;
>
{
    pass P0
    {
        VertexShader = <EarthVS_vectors>;
        VertexShaderConstantF[0]  = <World>;
        VertexShaderConstantF[8]  = <WorldViewProjection>;
        VertexShaderConstantF[12] = <LightDirection>;
        VertexShaderConstantF[14] = <CameraPosition>;

        Sampler[0] = (EarthSampler);
        Sampler[1] = (NormalSampler);
        PixelShaderConstantF[1] = <SpecularPower>;
        PixelShaderConstantF[2] = <SpecularColor>;

        PixelShader = asm
        {
            ps_2_0
            dcl t0.xy                   // surface coordinates
            dcl t1.xyz                  // light vector, tangent space
            dcl t2.xyz                  // half angle, tangent space
            dcl_2d s0                   // Earth
            dcl_2d s1                   // normal map
            def c0, 2.0, 1.0, 0.0, 0.0
            // c1.x = specular power, c2 = specular colour

            texld r0, t0, s0            // r0 = base
            texld r1, t0, s1            // r1 = packed normal
            mad r1.xyz, r1, c0.x, -c0.y // [0..1] => [-1..1]
            nrm r2.xyz, r1              // r2 = unit normal (after filtering)
            nrm r3.xyz, t1              // r3 = unit light vector
            nrm r4.xyz, t2              // r4 = unit half angle

            dp3_sat r5, r2, r3          // r5 = N.L
            dp3_sat r6, r2, r4          // r6 = N.H
            pow r6, r6.x, c1.x          // r6 = N.H ^ power
            mul r6, r6, c2              // * specular colour
            mad r0, r0, r5, r6          // base * diffuse + specular
            mov oC0, r0
        };
    }
}

// DX8: the chapter's table-lookup exponent. texm3x2pad/texm3x2tex compute u = N.L (the light
// direction in t1's coordinates) and v = N.H (half angle in t2's) and read the table at
// (u, v): rgb = v^SpecularPower, alpha = u. The dependent read gives the table's filtered
// precision instead of 8-bit products, so the highlight is smooth. The half angle is the
// vertex shader's, interpolated and not renormalised (texm3x2tex takes it as coordinates): on
// the default sphere (vertices 7.5 degrees apart) it runs up to 0.2 % short, which N.H^100
// turns into a highlight a third the ps_2_0 one's area (49 against 133 pixels above half at
// 128 x 128; within 10 % at 16 and on a sphere of 96 x 192 quads at 16, 48 and 100:
// tests/looks/test_power_tables.py).
technique SpecularTable_ps11
<
    string Description = "ps.1.1 exponent by table lookup (texm3x2pad / texm3x2tex)";
    int Quality = 6;
    float Cost = 5.0;
>
{
    pass P0
    {
        VertexShader = <EarthVS_vectors>;
        VertexShaderConstantF[0]  = <World>;
        VertexShaderConstantF[8]  = <WorldViewProjection>;
        VertexShaderConstantF[12] = <LightDirection>;
        VertexShaderConstantF[14] = <CameraPosition>;

        Texture[0] = <NormalMap>;
        Texture[1] = NULL;              // texm3x2pad: the stage's coordinates only
        Texture[2] = <PowerTable>;
        Texture[3] = <EarthTexture>;
        AddressU[2] = Clamp;            // u, v outside [0, 1] are N.L, N.H < 0: no light
        AddressV[2] = Clamp;
        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
        MinFilter[2] = Linear;
        MagFilter[2] = Linear;
        MinFilter[3] = Linear;
        MagFilter[3] = Linear;
        MipFilter[3] = Linear;

        PixelShader = asm
        {
            ps.1.1                      // exponentiation by table lookup

            //  texcoord t1      // the diffuse light direction
            //  texcoord t2      // half-angle vector
            //  texture at stage t2 is a table lookup function

            tex t0                      // sample the normal map
            texm3x2pad t1, t0_bx2       // 1st row of mult, 1st dotproduct=u
            texm3x2tex t2, t0_bx2       // 2nd row of mult, 2nd dotproduct=v
            tex t3                      // colour map (the chapter reads t3 without this)

            //assemble final color
            mad r0, t3, t2.a, t2        // colour map * diffuse (u) + specular (v^16)
        };
    }
}

// DX8: the chapter's multiply-based exponent: N.H squared four times is N.H^16. Each product
// is held at 8 bits, so the highlight shows bands (the chapter's Figure 5).
technique SpecularMultiply_ps11
<
    string Description = "ps.1.1 exponent by repeated multiplies (^16, banding)";
    int Quality = 5;
    float Cost = 9.0;
>
{
    pass P0
    {
        VertexShader = <EarthVS_colors>;
        VertexShaderConstantF[0]  = <World>;
        VertexShaderConstantF[8]  = <WorldViewProjection>;
        VertexShaderConstantF[12] = <LightDirection>;
        VertexShaderConstantF[14] = <CameraPosition>;

        Texture[0] = <EarthTexture>;
        Texture[1] = <NormalMap>;
        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
        MipFilter[0] = Linear;
        MinFilter[1] = Linear;
        MagFilter[1] = Linear;

        PixelShader = asm
        {
            ps.1.1                      // pow2 by multiplies
            tex t0                      // color map
            tex t1                      // normal map

            dp3_sat r1, t1_bx2, v0_bx2  // diffuse: N.L, v0 = light vector
            dp3_sat r0, t1_bx2, v1_bx2  // specular: N.H, v1 = half angle

            mul r0, r0, r0              //  2nd power
            mul r0, r0, r0              //  4th power
            mul r0, r0, r0              //  8th power
            mul r0, r0, r0              // 16th power!

            //assemble final color
            mad r0, r1, t0, r0          // color map * diffuse + specular
        };
    }
}

// DX7: the chapter's D3DTOP_DOTPRODUCT3 multi-texture setup; the operator applies _bx2 and
// _sat itself, so the normal map must be biased art (0.5*n + 0.5) and N.L cannot go negative.
technique Dot3_dx7
<
    string Description = "DOTPRODUCT3 of normal map and light vector (diffuse colour), times the Earth";
    int Quality = 4;
    float Cost = 2.0;
>
{
    pass P0
    {
        VertexShader = <EarthVS_colors>;
        VertexShaderConstantF[0]  = <World>;
        VertexShaderConstantF[8]  = <WorldViewProjection>;
        VertexShaderConstantF[12] = <LightDirection>;
        VertexShaderConstantF[14] = <CameraPosition>;
        PixelShader = NULL;

        ColorOp[0]   = DotProduct3;
        ColorArg1[0] = Texture;
        ColorArg2[0] = Diffuse;

        ColorOp[1]   = Modulate;
        ColorArg1[1] = Texture;
        ColorArg2[1] = Current;

        Texture[0]   = <NormalMap>;
        Texture[1]   = <EarthTexture>;

        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
        MinFilter[1] = Linear;
        MagFilter[1] = Linear;
        MipFilter[1] = Linear;
    }
}

// DX6: the chapter's listing, state for state:
//   0   MODULATE( EarthTexture, Diffuse );   // light the base texture
//   1   BUMPENVMAP( BumpMap, _ );            // sample bump map (other arg ignored)
//   2   ADD( EnvMapTexture, Current );       // sample envt map using bumped texcoords
//                                            // and add to result
// with the vertices the application made (EarthVS_envmap: lit colour, view-dependent
// environment coordinates). BUMPENVMAT scales the bump map's (du, dv) by k, the coordinates'
// own scale, so a bump tilts the lookup as far as the same tilt of the normal would.
technique BumpEnvMap_dx6
<
    string Description = "DX6 BUMPENVMAP: base x diffuse, bump-perturbed environment map added";
    int Quality = 3;
    float Cost = 3.0;
>
{
    pass P0
    {
        VertexShader = <EarthVS_envmap>;
        VertexShaderConstantF[0]  = <World>;
        VertexShaderConstantF[8]  = <WorldViewProjection>;
        VertexShaderConstantF[12] = <LightDirection>;
        VertexShaderConstantF[14] = <CameraPosition>;
        VertexShaderConstantF[16] = <LightColor>;
        PixelShader  = NULL;

        Wrap0 = 3;                      // D3DWRAP_U | D3DWRAP_V

        Texture[0]       = <EarthTexture>;
        ColorOp[0]       = Modulate;
        ColorArg1[0]     = Texture;
        ColorArg2[0]     = Diffuse;

        Texture[1]       = <BumpMap>;
        ColorOp[1]       = BumpEnvMap;
        ColorArg1[1]     = Texture;
        ColorArg2[1]     = Current;
        BumpEnvMat00[1]  = 0.32;
        BumpEnvMat01[1]  = 0.0;
        BumpEnvMat10[1]  = 0.0;
        BumpEnvMat11[1]  = 0.32;
        BumpEnvLScale[1]  = 4.0;
        BumpEnvLOffset[1] = 0.0;

        Texture[2]       = <EnvMapTexture>;
        ColorOp[2]       = Add;
        ColorArg1[2]     = Texture;
        ColorArg2[2]     = Current;
        AddressU[2]      = Clamp;       // off the spot the light map is black
        AddressV[2]      = Clamp;
        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
        MinFilter[1] = Linear;
        MagFilter[1] = Linear;
        MinFilter[2] = Linear;
        MagFilter[2] = Linear;
    }
}

// DX6 without bump mapping: the chapter's emboss. Pass 0 is its D3DTOP_ADDSIGNED setup
// (height map, plus the complement of the height map shifted toward the light, minus a half:
// 0.5 + h(uv) - h(uv + shift)); needs two simultaneous textures and ADDSIGNED, nothing more.
// The chapter leaves the colour out; pass 1 multiplies in the Earth lit by N.L through the
// frame buffer, 2x (DestColor * SrcColor twice) to brighten, as the chapter suggests.
technique Emboss_dx6
<
    string Description = "emboss bump mapping (ADDSIGNED, COMPLEMENT), colour by 2x frame-buffer modulate";
    int Quality = 2;
    float Cost = 3.0;
>
{
    pass Emboss
    {
        VertexShader = <EarthVS_emboss>;
        VertexShaderConstantF[0]  = <World>;
        VertexShaderConstantF[8]  = <WorldViewProjection>;
        VertexShaderConstantF[12] = <LightDirection>;
        VertexShaderConstantF[20] = { 0.5, 0.5, 0.5, 0.5 };
        VertexShaderConstantF[24] = <EmbossOffset>;
        PixelShader = NULL;

        ColorOp[0]   = SelectArg1;
        ColorArg1[0] = Texture;

        ColorOp[1]   = AddSigned;
        ColorArg1[1] = Texture | Complement;
        ColorArg2[1] = Current;

        Texture[0]   = <HeightMap>;     // base height map
        Texture[1]   = <HeightMap>;     // normal height map (shifted coordinates)
        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
        MinFilter[1] = Linear;
        MagFilter[1] = Linear;
    }

    pass Colour
    {
        // Vertex shader and constants persist from pass Emboss: oT0 = Earth coordinates,
        // oD0 = N.L.
        Texture[0]   = <EarthTexture>;
        ColorOp[0]   = Modulate;
        ColorArg1[0] = Texture;
        ColorArg2[0] = Diffuse;
        MipFilter[0] = Linear;
        ColorOp[1]   = Disable;

        AlphaBlendEnable = True;
        SrcBlend  = DestColor;
        DestBlend = SrcColor;
        ZWriteEnable = False;
        ZFunc = LessEqual;
    }
}

// Last resort: one texture stage, fixed-function lighting.
technique SingleTexture
<
    string Description = "Earth texture x fixed-function diffuse lighting";
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
        LightDirection[0] = <LightDirection>;
        LightDiffuse[0]   = <LightColor>;
        MaterialDiffuse   = { 1.0, 1.0, 1.0, 1.0 };

        Texture[0]       = <EarthTexture>;
        TexCoordIndex[0] = 1;
        ColorOp[0]       = Modulate;
        ColorArg1[0]     = Texture;
        ColorArg2[0]     = Diffuse;
        MinFilter[0]     = Linear;
        MagFilter[0]     = Linear;
        MipFilter[0]     = Linear;
        ColorOp[1]       = Disable;
    }
}
