// shadows.fx -- omni-directional shadow mapping after Emil Persson, "Fragment level Phong
// illumination" (the Shadows section): a first pass renders, from the point light, the squared
// distance to the light into a floating-point cube map (D3DFMT_R32F); the lighting pass looks
// the map up in the direction from the light to the pixel and compares the stored value with
// the pixel's own squared distance times 0.97 ("multiply the distance with a constant slightly
// less than 1", so the allowed error is a percentage of the distance), and here also divided
// by (1 + tan(theta) a)^2 for a surface tilted theta from the light and a look-up up to `a`
// radians off the pixel's direction (see "The comparison's margin" below: without it his
// four offset look-ups darkened the lit top of an occluder by a fifth). 0 in shadow, 1 lit,
// multiplying diffuse only: the ambient stays visible in the shadow.
//
// Techniques in fallback order (D3DX takes the first the card validates):
//
//   Shadow4_R32F     ps.2.0 and an R32F cube render target (refrast, modern, and the ATI cards
//                    he wrote for: Radeon 9700, X1800, caps_profiles/radeon9700.yaml): Persson's
//                    anti-aliased version, four look-ups offset by his constants (1,2,-1),
//                    (2,-1,1), (-1,1,2) -- scaled here by ShadowSpread, since his offsets
//                    were in the units of a larger world -- averaged with 0.25 each
//   Shadow1_R32F     the same with one look-up (his first listing). Any card that runs it
//                    also runs Shadow4_R32F, so a card never selects it; render it by name
//                    (`effects render ... -t Shadow1_R32F`)
//   Shadow4_R16F     ps.2.0 cards with a half-float but no single-float cube render target
//                    (GeForce 6800 in caps_profiles: R16F cube + rendertarget, R32F not as a
//                    cube): the same squared distance and four look-ups in an R16F cube map.
//                    A half holds it to 1 part in 2048 (10-bit mantissa), far inside the 3 %
//                    bias; its largest value is 65504, so the map clears to FarAway16 (past a
//                    distance of 244 nothing is shadowed)
//   Shadow4_Linear8  ps.2.0 cards without float cube render targets (GeForce FX, GMA 900:
//                    "some pixel shader 2.0 hardware doesn't support floating
//                    point cubemaps"): his advice, the linear distance, here divided by
//                    ShadowRange into an A8R8G8B8 cube map; the same 0.97 factor (8 bits of
//                    a 10-unit range are 0.04 units, under 3 % of any distance past 1.4)
//   Lit_ff           everything else: the same point light by fixed-function lighting, no shadow
//
// The render targets are said in the file (DXSAS Script annotations, effects/host/scripts.py):
// the cube targets carry `string ResourceType = "Cube"` (FX Composer's spelling) and
// `string CubeOrigin = "LightPosition"`; while the shadow pass draws into one, the host draws
// each of the six faces with WorldViewProjection bound to that face's view from the light.
//
//   effects render fxfiles/shadows.fx -p refrast --scene fxfiles/shadows.yaml -o shadows.png

//----------------------------------------------------------------------------------------------
// Parameters

float4x4 WorldViewProjection : WORLDVIEWPROJECTION;
float4x4 World               : WORLD;

float4 LightPosition : LIGHTPOSITION
<
    string UIName = "Point light position (world space)";
    string Space = "World";
> = { 0.0, 4.0, 0.0, 1.0 };

float4 SurfaceColor
<
    string UIName = "Diffuse colour (light colour x material)";
    string UIWidget = "Color";
> = { 0.9, 0.85, 0.75, 0.0 };

float4 AmbientColor
<
    string UIName = "Ambient";
    string UIWidget = "Color";
> = { 0.1, 0.1, 0.12, 1.0 };

// Persson's c1: (bias factor, averaging factor, 0, 0); 1.0 for one look-up, 0.25 for four.
float4 ShadowFactors1 < string UIName = "Bias factor, weight (one look-up)"; > = { 0.97, 1.0, 0.0, 0.0 };
float4 ShadowFactors4 < string UIName = "Bias factor, weight (four look-ups)"; > = { 0.97, 0.25, 0.0, 0.0 };

// How far the extra look-ups are offset: his constants times this (world units). The offsets
// are fixed lengths, so an offset look-up reads the receiver itself a little nearer the light
// on a surface tilted from it; the slope term below widens the margin by exactly that (in the
// test scene, light 4 above the floor, 0.03 gives a 2.5-pixel edge, 0.05 a 4.5-pixel one, both
// with the floor and the occluder's top clean).
float ShadowSpread
<
    string UIName = "Soft edge: look-up offset scale";
    float UIMin = 0.0;
    float UIMax = 0.1;
> = 0.03;

// How far (radians) the direction a texel was drawn for may lie from a look-up's: half a
// texel's diagonal for the nearest texel, and half again for Direct3D 9's pixel centres at
// integer positions, where texel centres sit at +0.5 -- 2 sqrt(2) / 256 for the 256-wide maps
// (a cube face spans tan -1..1 over its width; the angle is largest at the face's centre).
float ShadowTexelAngle < string UIName = "Shadow texel angle (radians)"; > = 0.011;

// The linear fallback stores distance / ShadowRange; this is 1 / ShadowRange (10 units).
float InverseShadowRange < string UIName = "1 / shadow range (8-bit fallback)"; > = 0.1;

float4 FarAway = { 1.0e6, 1.0e6, 1.0e6, 1.0e6 };   // nothing drawn there: never in shadow
float4 FarAway16 = { 60000.0, 60000.0, 60000.0, 60000.0 };   // under the half maximum 65504
float4 White = { 1.0, 1.0, 1.0, 1.0 };             // the linear map's "nothing": the full range
float4 Background = { 0.05, 0.05, 0.08, 1.0 };
float OneDepth = 1.0;

texture ShadowCube32 : RENDERCOLORTARGET
<
    string ResourceType = "Cube";
    string Format = "R32F";
    int Width = 256;
    string CubeOrigin = "LightPosition";
    float2 CubeDepthRange = { 0.05, 50.0 };
>;

texture ShadowCube16 : RENDERCOLORTARGET
<
    string ResourceType = "Cube";
    string Format = "R16F";
    int Width = 256;
    string CubeOrigin = "LightPosition";
    float2 CubeDepthRange = { 0.05, 50.0 };
>;

texture ShadowCube8 : RENDERCOLORTARGET
<
    string ResourceType = "Cube";
    string Format = "A8R8G8B8";
    int Width = 256;
    string CubeOrigin = "LightPosition";
    float2 CubeDepthRange = { 0.05, 50.0 };
>;

// Point sampling: a filtered depth would blend occluder and receiver (and R32F filters on
// none of the DX9 cards).
sampler ShadowSampler32 = sampler_state
{
    Texture = <ShadowCube32>;
    MinFilter = Point; MagFilter = Point; MipFilter = None;
    AddressU = Clamp; AddressV = Clamp; AddressW = Clamp;
};

sampler ShadowSampler16 = sampler_state
{
    Texture = <ShadowCube16>;
    MinFilter = Point; MagFilter = Point; MipFilter = None;
    AddressU = Clamp; AddressV = Clamp; AddressW = Clamp;
};

sampler ShadowSampler8 = sampler_state
{
    Texture = <ShadowCube8>;
    MinFilter = Point; MagFilter = Point; MipFilter = None;
    AddressU = Clamp; AddressV = Clamp; AddressW = Clamp;
};

//----------------------------------------------------------------------------------------------
// The shadow pass (Persson's "pair of simple shaders"; the vertex taken to world space first,
// since his scene had no world transform)

VertexShader ShadowVS = asm
{
    vs.2.0
    dcl_position v0
    // c0-c3 = mvp matrix (the cube face's), c4-c7 = world, c8 = light position
    m4x4     oPos, v0, c0
    m4x4     r1, v0, c4
    sub      oT0, c8, r1       // oT0 = light vector
};

PixelShader ShadowSquaredPS = asm
{
    ps.2.0
    dcl      t0
    dp3      r0, t0, t0        // the squared distance to the light
    mov      oC0, r0
};

PixelShader ShadowLinearPS = asm
{
    ps.2.0
    dcl      t0
    // c0.x = 1 / ShadowRange
    dp3      r0.x, t0, t0
    rsq      r0.x, r0.x
    rcp      r0.x, r0.x        // the distance to the light
    mul      r0, r0.x, c0.x    // in 0..1 over the range
    mov      oC0, r0
};

//----------------------------------------------------------------------------------------------
// The lighting pass: diffuse N.L from the point light (no attenuation) times the shadow
// factor, plus ambient.

VertexShader LightVS = asm
{
    vs.2.0
    dcl_position v0
    dcl_normal   v1
    // c0-c3 = mvp, c4-c7 = world, c8 = light position, c9.x = ShadowSpread
    def      c10, 1.0, 2.0, -1.0, 0.0
    def      c11, 2.0, -1.0, 1.0, 0.0
    def      c12, -1.0, 1.0, 2.0, 0.0
    m4x4     oPos, v0, c0
    m4x4     r1, v0, c4
    sub      r0, c8, r1        // r0 = light vector
    mov      oT0, r0
    m3x3     oT1.xyz, v1, c4   // world normal
    mov      oT3, -r0          // oT3 = shadow map
    mad      oT4, c10, c9.x, -r0
    mad      oT5, c11, c9.x, -r0
    mad      oT6, c12, c9.x, -r0
};

// The comparison's margin (Persson's bias factor, c1.x) shrinks with the surface's slope to the
// light: a look-up reads a texel drawn for a direction up to `a` radians off the pixel's own
// (the texel's size, and for the four-sample shaders the offset), and on a surface tilted by
// theta from the light direction that ray meets the same surface nearer the light, by a factor
// of up to 1 / (1 + tan(theta) a) in distance. So the stored value is compared with
//   biasfactor * d^2 / (1 + tan(theta) a)^2     (squared-distance maps)
//   biasfactor * d / range / (1 + tan(theta) a)  (the linear map)
// where a = ShadowTexelAngle (+ |offset| / d = sqrt(6) ShadowSpread / d with four look-ups:
// his offsets (1,2,-1), (2,-1,1), (-1,1,2) are all sqrt(6) long). Without the slope term the
// offset look-ups on the lit top of the test scene's cube land on the top itself nearer the
// light and darken it by a fifth (measured: red 164 where Lambert gives 207); the texel term
// keeps the default sphere free of acne near its terminator. tan(theta) = sqrt(1/c^2 - 1) for
// c = N.L, c kept at least 0.01 (where N.L is that small the diffuse it scales is nothing).

PixelShader Light1PS = asm
{
    ps.2.0
    dcl      t0
    dcl      t1
    dcl      t3
    dcl_cube s3
    // c1 = (bias factor, averaging factor, 0, 0), c2 = ambient, c3 = diffuse colour,
    // c5.x = ShadowTexelAngle
    def      c6, 1.0, 1.0e-8, 0.01, 2.4494897   // 1, a tiny tan^2, the least N.L, sqrt(6)
    texld    r8, t3, s3        // r8 = shadow map
    dp3      r7.x, t0, t0      // r7.x = lengthSqr(light vector)
    rsq      r6.x, r7.x
    mul      r6, t0, r6.x      // L
    dp3      r5.x, t1, t1
    rsq      r5.x, r5.x
    mul      r5, t1, r5.x      // N
    dp3_sat  r4.x, r5, r6      // N.L
    max      r3.x, r4.x, c6.z
    rcp      r3.x, r3.x
    mad      r3.x, r3.x, r3.x, -c6.x
    max      r3.x, r3.x, c6.y  // tan^2(theta) = 1/(N.L)^2 - 1
    rsq      r3.x, r3.x
    rcp      r3.x, r3.x        // tan(theta)
    mad      r3.x, r3.x, c5.x, c6.x
    mul      r3.x, r3.x, r3.x
    rcp      r3.x, r3.x        // 1 / (1 + tan(theta) a)^2
    mul      r4, r4.x, c3
    mul      r8.y, r7.x, c1.x  // r8.y = lengthSqr(light vector) * biasfactor
    mul      r8.y, r8.y, r3.x  // ... less the slope's share
    sub      r8.x, r8.x, r8.y
    cmp      r8.x, r8.x, c1.y, c1.z // r8.x = shadow factor
    mul      r4, r4, r8.x      // diffuse *= shadow factor
    add      r4, r4, c2        // + ambient
    mov      oC0, r4
};

PixelShader Light4PS = asm
{
    ps.2.0
    dcl      t0
    dcl      t1
    dcl      t3
    dcl      t4
    dcl      t5
    dcl      t6
    dcl_cube s3
    // c4.x = ShadowSpread, c5.x = ShadowTexelAngle
    def      c6, 1.0, 1.0e-8, 0.01, 2.4494897
    texld    r8, t3, s3
    texld    r9, t4, s3
    texld    r10, t5, s3
    texld    r11, t6, s3
    dp3      r7.x, t0, t0
    rsq      r6.x, r7.x
    mul      r3.y, r6.x, c4.x  // ShadowSpread / d
    mad      r3.y, r3.y, c6.w, c5.x // a = texel angle + |offset| / d
    mul      r6, t0, r6.x
    dp3      r5.x, t1, t1
    rsq      r5.x, r5.x
    mul      r5, t1, r5.x
    dp3_sat  r4.x, r5, r6
    max      r3.x, r4.x, c6.z
    rcp      r3.x, r3.x
    mad      r3.x, r3.x, r3.x, -c6.x
    max      r3.x, r3.x, c6.y
    rsq      r3.x, r3.x
    rcp      r3.x, r3.x        // tan(theta)
    mad      r3.x, r3.x, r3.y, c6.x
    mul      r3.x, r3.x, r3.x
    rcp      r3.x, r3.x        // 1 / (1 + tan(theta) a)^2
    mul      r4, r4.x, c3
    mul      r8.y, r7.x, c1.x
    mul      r8.y, r8.y, r3.x
    sub      r8.x, r8.x, r8.y
    sub      r9.x, r9.x, r8.y
    sub      r10.x, r10.x, r8.y
    sub      r11.x, r11.x, r8.y
    cmp      r8.x, r8.x, c1.y, c1.z
    cmp      r9.x, r9.x, c1.y, c1.z
    cmp      r10.x, r10.x, c1.y, c1.z
    cmp      r11.x, r11.x, c1.y, c1.z
    add      r8.x, r8.x, r9.x
    add      r8.x, r8.x, r10.x
    add      r8.x, r8.x, r11.x
    mul      r4, r4, r8.x
    add      r4, r4, c2
    mov      oC0, r4
};

// The linear fallback: the same comparison on distance / range (c0.x = 1 / range), the slope
// term once (a distance, not its square).
PixelShader Light4LinearPS = asm
{
    ps.2.0
    dcl      t0
    dcl      t1
    dcl      t3
    dcl      t4
    dcl      t5
    dcl      t6
    dcl_cube s3
    def      c6, 1.0, 1.0e-8, 0.01, 2.4494897
    texld    r8, t3, s3
    texld    r9, t4, s3
    texld    r10, t5, s3
    texld    r11, t6, s3
    dp3      r7.x, t0, t0
    rsq      r6.x, r7.x
    mul      r3.y, r6.x, c4.x
    mad      r3.y, r3.y, c6.w, c5.x // a = texel angle + |offset| / d
    rcp      r7.x, r6.x        // the distance
    mul      r7.x, r7.x, c0.x  // over the range
    mul      r6, t0, r6.x
    dp3      r5.x, t1, t1
    rsq      r5.x, r5.x
    mul      r5, t1, r5.x
    dp3_sat  r4.x, r5, r6
    max      r3.x, r4.x, c6.z
    rcp      r3.x, r3.x
    mad      r3.x, r3.x, r3.x, -c6.x
    max      r3.x, r3.x, c6.y
    rsq      r3.x, r3.x
    rcp      r3.x, r3.x        // tan(theta)
    mad      r3.x, r3.x, r3.y, c6.x
    rcp      r3.x, r3.x        // 1 / (1 + tan(theta) a)
    mul      r4, r4.x, c3
    mul      r8.y, r7.x, c1.x
    mul      r8.y, r8.y, r3.x
    sub      r8.x, r8.x, r8.y
    sub      r9.x, r9.x, r8.y
    sub      r10.x, r10.x, r8.y
    sub      r11.x, r11.x, r8.y
    cmp      r8.x, r8.x, c1.y, c1.z
    cmp      r9.x, r9.x, c1.y, c1.z
    cmp      r10.x, r10.x, c1.y, c1.z
    cmp      r11.x, r11.x, c1.y, c1.z
    add      r8.x, r8.x, r9.x
    add      r8.x, r8.x, r10.x
    add      r8.x, r8.x, r11.x
    mul      r4, r4, r8.x
    add      r4, r4, c2
    mov      oC0, r4
};

//----------------------------------------------------------------------------------------------
// Techniques

technique Shadow4_R32F
<
    int Quality = 3;
    float Cost = 48;
    string Script = "RenderColorTarget0=ShadowCube32; ClearSetColor=FarAway; ClearSetDepth=OneDepth;"
                    "Clear=Color; Clear=Depth; Pass=ShadowPass;"
                    "RenderColorTarget0=; ClearSetColor=Background; Clear=Color; Clear=Depth;"
                    "Pass=LightPass;";
>
{
    pass ShadowPass
    {
        CullMode = None; ZEnable = true; ZWriteEnable = true;
        VertexShader = <ShadowVS>;
        VertexShaderConstantF[0] = <WorldViewProjection>;
        VertexShaderConstantF[4] = <World>;
        VertexShaderConstantF[8] = <LightPosition>;
        PixelShader = <ShadowSquaredPS>;
    }
    pass LightPass
    {
        CullMode = None; ZEnable = true; ZWriteEnable = true;
        VertexShader = <LightVS>;
        VertexShaderConstantF[0] = <WorldViewProjection>;
        VertexShaderConstantF[4] = <World>;
        VertexShaderConstantF[8] = <LightPosition>;
        VertexShaderConstantF[9] = <ShadowSpread>;
        Sampler[3] = (ShadowSampler32);
        PixelShaderConstantF[1] = <ShadowFactors4>;
        PixelShaderConstantF[2] = <AmbientColor>;
        PixelShaderConstantF[3] = <SurfaceColor>;
        PixelShaderConstantF[4] = <ShadowSpread>;
        PixelShaderConstantF[5] = <ShadowTexelAngle>;
        PixelShader = <Light4PS>;
    }
}

technique Shadow1_R32F
<
    int Quality = 2;
    float Cost = 24;
    string Script = "RenderColorTarget0=ShadowCube32; ClearSetColor=FarAway; ClearSetDepth=OneDepth;"
                    "Clear=Color; Clear=Depth; Pass=ShadowPass;"
                    "RenderColorTarget0=; ClearSetColor=Background; Clear=Color; Clear=Depth;"
                    "Pass=LightPass;";
>
{
    pass ShadowPass
    {
        CullMode = None; ZEnable = true; ZWriteEnable = true;
        VertexShader = <ShadowVS>;
        VertexShaderConstantF[0] = <WorldViewProjection>;
        VertexShaderConstantF[4] = <World>;
        VertexShaderConstantF[8] = <LightPosition>;
        PixelShader = <ShadowSquaredPS>;
    }
    pass LightPass
    {
        CullMode = None; ZEnable = true; ZWriteEnable = true;
        VertexShader = <LightVS>;
        VertexShaderConstantF[0] = <WorldViewProjection>;
        VertexShaderConstantF[4] = <World>;
        VertexShaderConstantF[8] = <LightPosition>;
        VertexShaderConstantF[9] = <ShadowSpread>;
        Sampler[3] = (ShadowSampler32);
        PixelShaderConstantF[1] = <ShadowFactors1>;
        PixelShaderConstantF[2] = <AmbientColor>;
        PixelShaderConstantF[3] = <SurfaceColor>;
        PixelShaderConstantF[5] = <ShadowTexelAngle>;
        PixelShader = <Light1PS>;
    }
}

technique Shadow4_R16F
<
    int Quality = 3;
    float Cost = 48;
    string Script = "RenderColorTarget0=ShadowCube16; ClearSetColor=FarAway16; ClearSetDepth=OneDepth;"
                    "Clear=Color; Clear=Depth; Pass=ShadowPass;"
                    "RenderColorTarget0=; ClearSetColor=Background; Clear=Color; Clear=Depth;"
                    "Pass=LightPass;";
>
{
    pass ShadowPass
    {
        CullMode = None; ZEnable = true; ZWriteEnable = true;
        VertexShader = <ShadowVS>;
        VertexShaderConstantF[0] = <WorldViewProjection>;
        VertexShaderConstantF[4] = <World>;
        VertexShaderConstantF[8] = <LightPosition>;
        PixelShader = <ShadowSquaredPS>;
    }
    pass LightPass
    {
        CullMode = None; ZEnable = true; ZWriteEnable = true;
        VertexShader = <LightVS>;
        VertexShaderConstantF[0] = <WorldViewProjection>;
        VertexShaderConstantF[4] = <World>;
        VertexShaderConstantF[8] = <LightPosition>;
        VertexShaderConstantF[9] = <ShadowSpread>;
        Sampler[3] = (ShadowSampler16);
        PixelShaderConstantF[1] = <ShadowFactors4>;
        PixelShaderConstantF[2] = <AmbientColor>;
        PixelShaderConstantF[3] = <SurfaceColor>;
        PixelShaderConstantF[4] = <ShadowSpread>;
        PixelShaderConstantF[5] = <ShadowTexelAngle>;
        PixelShader = <Light4PS>;
    }
}

technique Shadow4_Linear8
<
    int Quality = 2;
    float Cost = 50;
    string Script = "RenderColorTarget0=ShadowCube8; ClearSetColor=White; ClearSetDepth=OneDepth;"
                    "Clear=Color; Clear=Depth; Pass=ShadowPass;"
                    "RenderColorTarget0=; ClearSetColor=Background; Clear=Color; Clear=Depth;"
                    "Pass=LightPass;";
>
{
    pass ShadowPass
    {
        CullMode = None; ZEnable = true; ZWriteEnable = true;
        VertexShader = <ShadowVS>;
        VertexShaderConstantF[0] = <WorldViewProjection>;
        VertexShaderConstantF[4] = <World>;
        VertexShaderConstantF[8] = <LightPosition>;
        PixelShaderConstantF[0] = <InverseShadowRange>;
        PixelShader = <ShadowLinearPS>;
    }
    pass LightPass
    {
        CullMode = None; ZEnable = true; ZWriteEnable = true;
        VertexShader = <LightVS>;
        VertexShaderConstantF[0] = <WorldViewProjection>;
        VertexShaderConstantF[4] = <World>;
        VertexShaderConstantF[8] = <LightPosition>;
        VertexShaderConstantF[9] = <ShadowSpread>;
        Sampler[3] = (ShadowSampler8);
        PixelShaderConstantF[0] = <InverseShadowRange>;
        PixelShaderConstantF[1] = <ShadowFactors4>;
        PixelShaderConstantF[2] = <AmbientColor>;
        PixelShaderConstantF[3] = <SurfaceColor>;
        PixelShaderConstantF[4] = <ShadowSpread>;
        PixelShaderConstantF[5] = <ShadowTexelAngle>;
        PixelShader = <Light4LinearPS>;
    }
}

technique Lit_ff
<
    int Quality = 1;
    float Cost = 1;
    // the same background as the shadowed techniques (without it the scene's clear, black)
    string Script = "ClearSetColor=Background; Clear=Color; Clear=Depth; Pass=P0;";
>
{
    pass P0
    {
        CullMode = None;
        VertexShader = NULL; PixelShader = NULL;
        Lighting = true;
        LightEnable[0] = true;
        LightType[0] = Point;
        LightPosition[0] = <LightPosition>;
        LightDiffuse[0] = { 1.0, 1.0, 1.0, 1.0 };
        LightAmbient[0] = { 0.0, 0.0, 0.0, 0.0 };
        LightAttenuation0[0] = 1.0;
        LightRange[0] = 100.0;
        Ambient = 0xff1a1a1f;
        MaterialDiffuse = <SurfaceColor>;
        MaterialAmbient = { 1.0, 1.0, 1.0, 1.0 };
        ColorOp[0] = SelectArg1; ColorArg1[0] = Diffuse;
        AlphaOp[0] = SelectArg1; AlphaArg1[0] = Diffuse;
    }
}
