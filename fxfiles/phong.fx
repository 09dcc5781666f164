// phong.fx -- fragment-level Phong illumination after Emil Persson, "Fragment level Phong
// illumination": I = base*ambient + Att * LightColor * (base * (N.L) + gloss * (R.V)^24),
// Att = 1 / (c + q*r^2), N from a normal map made from a height map by a Sobel filter,
// everything in tangent space. Techniques in fallback order (D3DX FindNextValidTechnique
// takes the first valid one, in file order):
//
//   PerPixelPhong_ps20   DX9  (Radeon 9700): Persson's ps.2.0 listing, true pow, 1 pass
//   PerPixelPhong_ps11   DX8  (GeForce3, Radeon 8500): dot3 diffuse, then the specular by the
//                        chapter's table lookup (N.H^96 ~ (R.V)^24), 2 passes added in the frame buffer
//   Dot3_dx7             DX7  (GeForce2): DOTPRODUCT3 texture stage, light vector in the
//                        diffuse colour, per-vertex specular added by SpecularEnable
//   SingleTexture        DX6 and anything else (TNT2, Voodoo3): fixed-function vertex lighting
//                        times the base texture
//
// Technique annotations (fxfiles/README.md): `int Quality` -- higher looks better, comparable
// inside this file; `float Cost` -- texture reads + arithmetic instruction slots (or active
// texture stages) per pixel, summed over passes.
//
// Texture annotation convention (fxfiles/README.md has the full list):
//   string ResourceName = "path"          an image file, relative to this effect file
//   string Procedural   = "gen:argument"  a texture made at load time by generator `gen`;
//                                         here "sobel_normals:<height image>" is Persson's
//                                         recipe: Sobel dX, dY of the height map, the vector
//                                         (dX, dY, 1) normalised, packed 0.5*n+0.5 in X8R8G8B8
//   string Type = "2D" | "CUBE" | "3D",  string Format = "X8R8G8B8" | "L8" | "V8U8" ...
//
// Vertex input (all techniques): position, normal, tangent (the u direction of the texture),
// texcoord0. Persson feeds the binormal too; here the shaders rebuild it as normal x tangent.
// Matrices loaded with VertexShaderConstantF are read by m4x4/m3x3 as rows of the transpose
// (the runtime loads them that way, as D3DX does for matrix parameters).

//----------------------------------------------------------------------------------------------
// Parameters

float4x4 WorldViewProjection : WORLDVIEWPROJECTION;
float4x4 World               : WORLD;
float4x4 View                : VIEW;
float4x4 Projection          : PROJECTION;

float4 CameraPosition : CAMERAPOSITION
<
    string UIName = "Eye position (world space)";
> = { 0.0, 0.0, 3.0, 1.0 };

float4 LightPosition : LIGHTPOSITION
<
    string UIName = "Point light position (world space)";
    string Space = "World";
> = { 2.0, 2.0, 2.0, 1.0 };

float4 LightColor : LIGHTCOLOR
<
    string UIName = "Light colour";
    string UIWidget = "Color";
> = { 1.0, 1.0, 1.0, 1.0 };

// Att = 1 / (AttenuationConstant + AttenuationQuadratic * r^2): Persson drops the linear term.
float AttenuationConstant
<
    string UIName = "Constant attenuation";
    float UIMin = 0.0;
    float UIMax = 4.0;
> = 1.0;

float AttenuationQuadratic
<
    string UIName = "Quadratic attenuation";
    float UIMin = 0.0;
    float UIMax = 1.0;
> = 0.05;

float4 AmbientColor
<
    string UIName = "Ambient";
    string UIWidget = "Color";
> = { 0.15, 0.15, 0.15, 1.0 };

// Persson: "We will use a constant specular exponent of 24".
float SpecularPower
<
    string UIName = "Specular exponent";
    float UIMin = 1.0;
    float UIMax = 128.0;
> = 24.0;

texture BaseTexture
<
    string ResourceName = "textures/stones_base.png";
    string Type = "2D";
>;

texture NormalMap
<
    string Procedural = "sobel_normals:textures/stones_height.png";
    string Type = "2D";
    string Format = "X8R8G8B8";
    int Width = 128;
    int Height = 128;
>;

// The gloss map: one channel, the specular coefficient (Persson: "a single channel texture").
texture GlossMap
<
    string ResourceName = "textures/stones_gloss.png";
    string Type = "2D";
    string Format = "L8";
>;

// The DX8 technique's specular table (the chapter's LightEval, fxfiles/README.md): at (u, v),
// rgb = v^(4 SpecularPower) and alpha = u: Blinn's N.H exponent that draws Phong's
// (R.V)^SpecularPower (96 for the article's 24). Made again whenever SpecularPower changes.
// 2048 rows, not the chapter's 256: N.H = 1 reads the last row, at 1 - 0.5/rows, and
// (1 - 0.5/256)^400 is 0.46 -- the highlight at SpecularPower 100 would lose half its
// brightness -- where (1 - 0.5/2048)^400 is 0.91. Only N.H (v) matters here (the specular
// pass uses rgb alone), so 64 columns do; 64 x 2048 is 128 Ki texels.
texture SpecularTable
<
    string Procedural = "power_table:4*<SpecularPower>";
    string Type = "2D";
    string Format = "A8R8G8B8";
    int Width = 64;
    int Height = 2048;
>;

sampler2D BaseSampler = sampler_state
{
    Texture = <BaseTexture>;
    MinFilter = Linear;
    MagFilter = Linear;
    MipFilter = Linear;
    AddressU = Wrap;
    AddressV = Wrap;
};

sampler2D NormalSampler = sampler_state
{
    Texture = <NormalMap>;
    MinFilter = Linear;
    MagFilter = Linear;
    MipFilter = Linear;
    AddressU = Wrap;
    AddressV = Wrap;
};

sampler2D GlossSampler = sampler_state
{
    Texture = <GlossMap>;
    MinFilter = Linear;
    MagFilter = Linear;
    MipFilter = Linear;
    AddressU = Wrap;
    AddressV = Wrap;
};

//----------------------------------------------------------------------------------------------
// Vertex shaders

// Persson's vertex shader (printed as vs.2.0; nothing in it needs more than vs_1_1), moved from
// object space to world space and with the binormal rebuilt from normal and tangent.
VertexShader PhongVS = asm
{
    vs_1_1
    dcl_position  v0
    dcl_normal    v3
    dcl_texcoord0 v7
    dcl_tangent   v8

    // c0-c3 = world*view*projection matrix
    // c4-c7 = world matrix
    // c8    = camera position (world)
    // c9    = light position (world)

    // Transform position
    m4x4 oPos, v0, c0

    // Output texcoord
    mov oT0.xy, v7

    // Tangent space basis in world space
    m4x4 r0, v0, c4                  // r0 = world position
    m3x3 r3.xyz, v8, c4              // r3 = tangent (u vector)
    m3x3 r5.xyz, v3, c4              // r5 = normal
    mul  r4.xyz, r5.yzx, r3.zxy
    mad  r4.xyz, -r5.zxy, r3.yzx, r4 // r4 = normal x tangent (v vector)

    sub r1, c9, r0                   // r1 = light vector
    dp3 oT1.x, r1, r3
    dp3 oT1.y, r1, r4
    dp3 oT1.z, r1, r5                // oT1 = light vector in tangent space

    sub r2, c8, r0                   // r2 = view vector
    dp3 oT2.x, r2, r3
    dp3 oT2.y, r2, r4
    dp3 oT2.z, r2, r5                // oT2 = view vector in tangent space
};

// DX8 path: unit light and half vectors in tangent space. For the diffuse pass the light
// vector is biased into oD0 for _bx2 in the pixel shader, as in the Direct3D chapter's
// diffuse setup; for the specular pass the light vector and the half angle go unbiased to
// oT1 and oT2, the chapter's table-lookup layout (the rows of texm3x2pad/texm3x2tex).
// oT0 = oT3 = surface coordinates (normal map; base or gloss map); light colour *
// attenuation (per vertex) in oD1.
VertexShader PhongVS_dx8 = asm
{
    vs_1_1
    dcl_position  v0
    dcl_normal    v3
    dcl_texcoord0 v7
    dcl_tangent   v8

    // c0-c3 = world*view*projection, c4-c7 = world
    // c8 = camera position, c9 = light position, c10 = light colour
    // c11.x = constant attenuation, c12.x = quadratic attenuation
    def c13, 0.5, 0.5, 0.5, 0.5

    m4x4 oPos, v0, c0
    mov oT0.xy, v7                   // normal map
    mov oT3.xy, v7                   // base map (diffuse pass), gloss map (specular pass)

    m4x4 r0, v0, c4                  // world position
    m3x3 r3.xyz, v8, c4              // tangent
    m3x3 r5.xyz, v3, c4              // normal
    mul  r4.xyz, r5.yzx, r3.zxy
    mad  r4.xyz, -r5.zxy, r3.yzx, r4 // binormal = normal x tangent

    sub r1, c9, r0                   // light vector
    dp3 r1.w, r1, r1                 // r1.w = squared distance to the light
    rsq r7.x, r1.w
    mul r1.xyz, r1, r7.x             // unit light vector

    sub r2, c8, r0                   // view vector
    dp3 r2.w, r2, r2
    rsq r7.y, r2.w
    mul r2.xyz, r2, r7.y             // unit view vector
    add r2.xyz, r2, r1               // half angle
    dp3 r2.w, r2, r2
    rsq r7.z, r2.w
    mul r2.xyz, r2, r7.z             // unit half angle

    dp3 r6.x, r1, r3
    dp3 r6.y, r1, r4
    dp3 r6.z, r1, r5
    mad oD0.xyz, r6.xyz, c13, c13    // light in oD0: multiply by a half then add half
    mov oT1.xyz, r6                  // not a tex coord: light direction (texm3x2pad row)

    dp3 r8.x, r2, r3
    dp3 r8.y, r2, r4
    dp3 r8.z, r2, r5
    mov oT2.xyz, r8                  // not a tex coord: half angle (texm3x2tex row)

    mul r9.x, c12.x, r1.w            // q * r^2
    add r9.x, r9.x, c11.x            // c + q * r^2 (vs_1_1 reads one constant per instruction)
    rcp r9.x, r9.x                   // attenuation
    mul oD1, c10, r9.x               // light colour * attenuation
};

// DX7 path: the tangent-space light vector, biased, in the diffuse colour for DOTPRODUCT3,
// and a per-vertex Blinn specular (lit) in the specular colour. DX7 cards run vs.1.1 through
// the runtime's software vertex processing, as the chapter's DOTPRODUCT3 fallback does.
VertexShader PhongVS_dx7 = asm
{
    vs_1_1
    dcl_position  v0
    dcl_normal    v3
    dcl_texcoord0 v7
    dcl_tangent   v8

    // c0-c3 = world*view*projection, c4-c7 = world
    // c8 = camera position, c9 = light position, c10 = light colour
    // c11.x = constant attenuation, c12.x = quadratic attenuation, c14.x = specular power
    def c13, 0.5, 0.5, 0.5, 0.5

    m4x4 oPos, v0, c0
    mov oT0.xy, v7                   // normal map
    mov oT1.xy, v7                   // base texture

    m4x4 r0, v0, c4
    m3x3 r3.xyz, v8, c4              // tangent
    m3x3 r5.xyz, v3, c4              // normal
    mul  r4.xyz, r5.yzx, r3.zxy
    mad  r4.xyz, -r5.zxy, r3.yzx, r4 // binormal

    sub r1, c9, r0
    dp3 r1.w, r1, r1
    rsq r7.x, r1.w
    mul r1.xyz, r1, r7.x             // unit light vector (world)

    sub r2, c8, r0
    dp3 r2.w, r2, r2
    rsq r7.y, r2.w
    mul r2.xyz, r2, r7.y
    add r2.xyz, r2, r1
    dp3 r2.w, r2, r2
    rsq r7.z, r2.w
    mul r2.xyz, r2, r7.z             // unit half angle (world)

    dp3 r6.x, r1, r3
    dp3 r6.y, r1, r4
    dp3 r6.z, r1, r5
    mad oD0.xyz, r6.xyz, c13, c13        // light vector for the DOTPRODUCT3 stage
    mov oD0.w, c13.w

    mov r10, c13                     // lit reads x, y and w: give every component a value
    dp3 r10.x, r5, r1                // N.L (vertex normal)
    dp3 r10.y, r5, r2                // N.H
    mov r10.w, c14.x                 // exponent
    lit r11, r10                     // r11.z = N.H ^ power where N.L > 0

    mul r9.x, c12.x, r1.w
    add r9.x, r9.x, c11.x
    rcp r9.x, r9.x                   // attenuation
    mul r11.z, r11.z, r9.x
    mul oD1.xyz, c10, r11.z          // specular colour, added after the stages
    mov oD1.w, c13.w
};

//----------------------------------------------------------------------------------------------
// Techniques, best first

// DX9: Persson's ps.2.0 pixel shader, assembled from the article's listings (diffuse,
// attenuation, specular with gloss, ambient). Changes to the printed code, all marked:
//   * the exponent comes from SpecularPower in c1.x instead of `def c0, 2.0, 1.0, 24.0, 0.0`;
//   * attenuation reads c2.x (constant) and c3.x (quadratic) where the article packs both in c2;
//   * ambient is a colour (c4) where the article uses the scalar c2.z; light colour (c5) is
//     multiplied in (the article's equation has it, its shader leaves it at white).
technique PerPixelPhong_ps20
<
    string Description = "ps.2.0 per-pixel Phong: normalised vectors, pow 24, gloss, attenuation, ambient";
    int Quality = 4;
    float Cost = 29.0;
>
{
    pass P0
    {
        VertexShader = <PhongVS>;
        VertexShaderConstantF[0] = <WorldViewProjection>;
        VertexShaderConstantF[4] = <World>;
        VertexShaderConstantF[8] = <CameraPosition>;
        VertexShaderConstantF[9] = <LightPosition>;

        Sampler[0] = (BaseSampler);
        Sampler[1] = (NormalSampler);
        Sampler[2] = (GlossSampler);

        PixelShaderConstantF[1] = <SpecularPower>;
        PixelShaderConstantF[2] = <AttenuationConstant>;
        PixelShaderConstantF[3] = <AttenuationQuadratic>;
        PixelShaderConstantF[4] = <AmbientColor>;
        PixelShaderConstantF[5] = <LightColor>;

        PixelShader = asm
        {
            ps_2_0

            dcl t0.xy
            dcl t1
            dcl t2

            dcl_2d s0
            dcl_2d s1
            dcl_2d s2

            def c0, 2.0, 1.0, 0.0, 0.0  // (2.0, 1.0, unused ...); exponent is c1.x

            texld    r0, t0, s0         // r0 = base
            texld    r1, t0, s1         // r1 = bump
            texld    r2, t0, s2         // r2 = gloss

            mad      r1.xyz, r1, c0.x, -c0.y  // bump[0..1] => bump[-1..1]

            dp3      r7.w, r1, r1
            rsq      r7.w, r7.w
            mul      r1.xyz, r1, r7.w   // r1 = post-filter normalized bumpmap

            dp3      r7, t1, t1
            rsq      r7.w, r7.x
            mul      r3, t1, r7.w       // r3 = normalized light vector

            // changed: c2.x = constant, c3.x = quadratic attenuation
            mad      r5, c3.x, r7, c2.x
            rcp      r5, r5.x           // r5 = attenuation

            dp3_sat  r4, r3, r1         // r4 = diffuse

            dp3      r7, t2, t2
            rsq      r7.w, r7.x
            mul      r6, t2, r7.w       // r6 = normalized view vector

            dp3      r7, r3, r1
            mul      r7, r7, c0.x
            mad      r3, r7, r1, -r3    // r3 = reflection vector

            dp3_sat  r3, r3, r6
            pow      r3, r3.x, c1.x     // r3 = specular (changed: exponent in c1.x)
            mul      r3, r3, r2         // r3 = specular * gloss

            mad      r4, r4, r0, r3     // r4 = base * diffuse + specular * gloss
            mul      r4, r4, r5         // r4 *= attenuation
            mul      r4, r4, c5         // added: r4 *= light colour
            mad      r4, r0, c4, r4     // r4 += base * ambient (changed: ambient colour c4)
            mov      oC0, r4
        };
    }
}

// DX8: ps.1.1 has 4 texture + 8 arithmetic slots and 8-bit fixed point. Pass 0 is the dot3
// diffuse and the ambient; pass 1 adds the specular by the chapter's table lookup
// (texm3x2pad/texm3x2tex: u = N.L, v = N.H, a dependent read of rgb = v^(4 SpecularPower),
// v^96 at the article's 24). Not the
// exponent by multiplies: the chapter advises against powers above 16 that way (8-bit
// products band), and 16 would be the wrong size. Blinn's N.H^96 stands for Persson's
// (R.V)^24: the angle between R and V is about twice the angle between N and H, so
// cos(2a)^24 ~ exp(-48 a^2) ~ cos(a)^96 -- the same width in the plane of incidence; across
// it Blinn's highlight is narrower, and measured on a finely tessellated sphere the table
// technique keeps 0.78, 0.69 and 0.60 of the ps.2.0 highlight's area at SpecularPower 16,
// 48 and 100 (tests/looks/test_power_tables.py).
technique PerPixelPhong_ps11
<
    string Description = "ps.1.1 dot3 diffuse + specular by table lookup (N.H^96 ~ (R.V)^24), two additive passes";
    int Quality = 3;
    float Cost = 11.0;
>
{
    pass Diffuse
    {
        VertexShader = <PhongVS_dx8>;
        VertexShaderConstantF[0]  = <WorldViewProjection>;
        VertexShaderConstantF[4]  = <World>;
        VertexShaderConstantF[8]  = <CameraPosition>;
        VertexShaderConstantF[9]  = <LightPosition>;
        VertexShaderConstantF[10] = <LightColor>;
        VertexShaderConstantF[11] = <AttenuationConstant>;
        VertexShaderConstantF[12] = <AttenuationQuadratic>;

        Texture[0] = <NormalMap>;
        Texture[3] = <BaseTexture>;
        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
        MipFilter[0] = Linear;
        MinFilter[3] = Linear;
        MagFilter[3] = Linear;
        MipFilter[3] = Linear;

        PixelShaderConstant[0] = <AmbientColor>;

        PixelShader = asm
        {
            ps.1.1
            tex t0                       // normal map
            tex t3                       // base texture

            dp3_sat r0, t0_bx2, v0_bx2   // N.L
            mad r0, r0, v1, c0           // * light colour * attenuation + ambient
            mul r0, r0, t3               // * base
        };
    }

    pass Specular
    {
        // Vertex shader and constants persist from the first pass.
        Texture[1] = NULL;               // texm3x2pad: the stage's coordinates only
        Texture[2] = <SpecularTable>;
        Texture[3] = <GlossMap>;
        AddressU[2] = Clamp;             // N.L, N.H < 0 land on the table's dark edge
        AddressV[2] = Clamp;
        MinFilter[2] = Linear;
        MagFilter[2] = Linear;
        MipFilter[2] = None;

        AlphaBlendEnable = True;
        SrcBlend = One;
        DestBlend = One;
        ZWriteEnable = False;
        ZFunc = LessEqual;

        PixelShader = asm
        {
            ps.1.1
            tex t0                       // normal map
            texm3x2pad t1, t0_bx2        // u = N.L (light direction in t1)
            texm3x2tex t2, t0_bx2        // v = N.H (half angle in t2); t2 = table(u, v)
            tex t3                       // gloss map

            mul r0, t2, t3               // N.H^96 * gloss
            mul r0, r0, v1               // * light colour * attenuation
        };
    }
}

// DX7: the chapter's DOTPRODUCT3 fallback (stage 0 dot3 of normal map and diffuse, stage 1
// modulate the colour map). DOTPRODUCT3 applies _bx2 and _sat itself. The diffuse colour
// holds the light vector, so this path has no light colour, attenuation or ambient on the
// diffuse term; the per-vertex specular comes in through SpecularEnable.
technique Dot3_dx7
<
    string Description = "DOTPRODUCT3 texture stage, light vector in the diffuse colour";
    int Quality = 2;
    float Cost = 2.0;
>
{
    pass P0
    {
        VertexShader = <PhongVS_dx7>;
        VertexShaderConstantF[0]  = <WorldViewProjection>;
        VertexShaderConstantF[4]  = <World>;
        VertexShaderConstantF[8]  = <CameraPosition>;
        VertexShaderConstantF[9]  = <LightPosition>;
        VertexShaderConstantF[10] = <LightColor>;
        VertexShaderConstantF[11] = <AttenuationConstant>;
        VertexShaderConstantF[12] = <AttenuationQuadratic>;
        VertexShaderConstantF[14] = <SpecularPower>;
        PixelShader = NULL;

        Texture[0]   = <NormalMap>;
        ColorOp[0]   = DotProduct3;
        ColorArg1[0] = Texture;
        ColorArg2[0] = Diffuse;
        AlphaOp[0]   = SelectArg1;
        AlphaArg1[0] = Diffuse;

        Texture[1]   = <BaseTexture>;
        ColorOp[1]   = Modulate;
        ColorArg1[1] = Texture;
        ColorArg2[1] = Current;
        AlphaOp[1]   = SelectArg1;
        AlphaArg1[1] = Current;

        ColorOp[2]   = Disable;
        AlphaOp[2]   = Disable;

        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
        MinFilter[1] = Linear;
        MagFilter[1] = Linear;
        MipFilter[1] = Linear;

        SpecularEnable = True;
    }
}

// Last resort, any card (a TNT2, a Voodoo3): fixed-function vertex lighting of one point
// light, times the base texture in one stage. No vertex or pixel shader.
technique SingleTexture
<
    string Description = "fixed-function vertex lighting x base texture";
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

        Lighting         = True;
        NormalizeNormals = True;
        SpecularEnable   = True;
        LightEnable[0]       = True;
        LightType[0]         = Point;
        LightPosition[0]     = <LightPosition>;
        LightDiffuse[0]      = <LightColor>;
        LightSpecular[0]     = <LightColor>;
        LightAmbient[0]      = <AmbientColor>;
        LightRange[0]        = 1000.0;
        LightAttenuation0[0] = <AttenuationConstant>;
        LightAttenuation1[0] = 0.0;
        LightAttenuation2[0] = <AttenuationQuadratic>;

        MaterialDiffuse  = { 1.0, 1.0, 1.0, 1.0 };
        MaterialAmbient  = { 1.0, 1.0, 1.0, 1.0 };
        MaterialSpecular = { 0.5, 0.5, 0.5, 1.0 };
        MaterialEmissive = { 0.0, 0.0, 0.0, 0.0 };
        MaterialPower    = <SpecularPower>;

        Texture[0]   = <BaseTexture>;
        ColorOp[0]   = Modulate;
        ColorArg1[0] = Texture;
        ColorArg2[0] = Diffuse;
        AlphaOp[0]   = SelectArg1;
        AlphaArg1[0] = Texture;
        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
        MipFilter[0] = Linear;

        ColorOp[1] = Disable;
        AlphaOp[1] = Disable;
    }
}
