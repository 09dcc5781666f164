// Look-alike of an engine's fixed-function shader (in the manner of Nebula2's fixed/*.fx;
// written for this project, not copied): shared matrices declared together, a typedef, light
// arrays sized by a static const, lights set from indexed parameters, two techniques (a lit
// one and an unlit fallback), the engine's own '#' remark inside an asm block (D3DX's
// assembler rejects it: a warning here).

typedef float4 color4;
shared float4x4 Model : World, View : View, Projection : Projection;
static const int NumLights = 2;
float4 LightPos[NumLights] = {{2.0, 2.0, -2.0, 1.0}, {-3.0, 0.5, -1.0, 1.0},};
color4 LightColor[NumLights] = {{1.0, 0.8, 0.6, 1.0}, {0.2, 0.3, 0.8, 1.0}};
color4 MatDiffuse < string UIName = "Diffuse"; > = {1.0, 1.0, 1.0, 1.0};
color4 MatAmbient = (float4)0;
int CullMode = 2;

texture DiffMap0 < string ResourceName = "textures/engine_diffuse.dds"; >;

technique tLit
{
    pass p0
    {
        WorldTransform[0] = <Model>;
        CullMode = <CullMode>;
        Lighting = true;
        LightEnable[0] = true; LightType[0] = Point;
        LightPosition[0] = <LightPos[0]>; LightDiffuse[0] = <LightColor[0]>;
        LightRange[0] = 100.0; LightAttenuation0[0] = 1.0;
        LightEnable[1] = true; LightType[1] = Point;
        LightPosition[1] = <LightPos[1]>; LightDiffuse[1] = <LightColor[1]>;
        LightRange[1] = 100.0; LightAttenuation0[1] = 1.0;
        MaterialDiffuse = <MatDiffuse>; MaterialAmbient = <MatAmbient>;
        Texture[0] = <DiffMap0>;
        ColorOp[0] = Modulate; ColorArg1[0] = Texture; ColorArg2[0] = Diffuse;
        AlphaOp[0] = SelectArg1; AlphaArg1[0] = Diffuse;
    }
}

technique tUnlit
{
    pass p0
    {
        PixelShader = asm {
            ps.1.1
            # engine: unlit fallback, texture times vertex colour
            tex t0
            mul r0, t0, v0
        };
        Texture[0] = <DiffMap0>;
    }
}
