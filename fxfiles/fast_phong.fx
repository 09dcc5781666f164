// fast_phong.fx -- Phong shading of the fixed-function pipeline: Gary Bishop and David M.
// Weimer, "Fast Phong Shading" (SIGGRAPH 1986). Direct3D named the shade mode
// (D3DSHADE_PHONG, with the caps bits D3DPSHADECAPS_COLORPHONGRGB / SPECULARPHONGRGB) and no
// card ever shaded with it; here the reference rasteriser (`refrast`) reports the bit. The
// lowering evaluates the vertex lighting equations per pixel with the normal interpolated and
// normalised at every pixel, which the GL back end draws; the NumPy reference back end draws
// the same lighting by the paper's Taylor form (a second-order series of N.L/|N| and
// N.H/(|N||H|) per triangle, the power from an 8K table), with the eye at infinity or, as
// LocalViewer = True says here, at a finite distance (backends/reference/taylor_lighting.py;
// the error against exact Phong: tests/looks/test_shade_phong.py). Techniques in fallback order:
//
//   Phong      ShadeMode = Phong: per-pixel lighting (refrast only)
//   Gouraud    the same lighting per vertex, interpolated (every card)
//
// One directional light, white diffuse, a tight specular (MaterialPower 40) so the facets of
// the Gouraud highlight show on the 24 x 48 sphere; no texture.

float4x4 World      : WORLD;
float4x4 View       : VIEW;
float4x4 Projection : PROJECTION;

float4 LightDirection : LIGHTDIRECTION
<
    string UIName = "Light direction (world space, the way the light travels)";
> = { -0.577, -0.577, -0.577, 0.0 };

float4 DiffuseColor  < string UIWidget = "Color"; > = { 0.75, 0.75, 0.75, 1.0 };
float4 SpecularColor < string UIWidget = "Color"; > = { 0.6, 0.6, 0.6, 1.0 };
float4 AmbientColor  < string UIWidget = "Color"; > = { 0.1, 0.1, 0.1, 1.0 };

float SpecularPower
<
    string UIName = "Specular exponent";
    float UIMin = 1.0;
    float UIMax = 128.0;
> = 40.0;

technique Phong
<
    string Description = "fixed-function lighting per pixel (ShadeMode = Phong, refrast)";
    int Quality = 2;
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

        ShadeMode         = Phong;
        Lighting          = True;
        SpecularEnable    = True;
        LocalViewer       = True;
        LightEnable[0]    = True;
        LightType[0]      = Directional;
        LightDirection[0] = <LightDirection>;
        LightDiffuse[0]   = { 1.0, 1.0, 1.0, 1.0 };
        LightSpecular[0]  = { 1.0, 1.0, 1.0, 1.0 };
        LightAmbient[0]   = { 0.0, 0.0, 0.0, 0.0 };
        Ambient           = <AmbientColor>;
        MaterialDiffuse   = <DiffuseColor>;
        MaterialAmbient   = { 1.0, 1.0, 1.0, 1.0 };
        MaterialSpecular  = <SpecularColor>;
        MaterialPower     = <SpecularPower>;
        ColorVertex       = False;

        ColorOp[0]   = SelectArg1;
        ColorArg1[0] = Diffuse;
        AlphaOp[0]   = SelectArg1;
        AlphaArg1[0] = Diffuse;
        ColorOp[1]   = Disable;
        AlphaOp[1]   = Disable;
    }
}

technique Gouraud
<
    string Description = "the same lighting per vertex (ShadeMode = Gouraud)";
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

        ShadeMode         = Gouraud;
        Lighting          = True;
        SpecularEnable    = True;
        LocalViewer       = True;
        LightEnable[0]    = True;
        LightType[0]      = Directional;
        LightDirection[0] = <LightDirection>;
        LightDiffuse[0]   = { 1.0, 1.0, 1.0, 1.0 };
        LightSpecular[0]  = { 1.0, 1.0, 1.0, 1.0 };
        LightAmbient[0]   = { 0.0, 0.0, 0.0, 0.0 };
        Ambient           = <AmbientColor>;
        MaterialDiffuse   = <DiffuseColor>;
        MaterialAmbient   = { 1.0, 1.0, 1.0, 1.0 };
        MaterialSpecular  = <SpecularColor>;
        MaterialPower     = <SpecularPower>;
        ColorVertex       = False;

        ColorOp[0]   = SelectArg1;
        ColorArg1[0] = Diffuse;
        AlphaOp[0]   = SelectArg1;
        AlphaArg1[0] = Diffuse;
        ColorOp[1]   = Disable;
        AlphaOp[1]   = Disable;
    }
}
