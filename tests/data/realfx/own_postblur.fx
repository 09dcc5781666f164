// A two-pass box blur as a DXSAS post-process, written for this project in the shape of
// NVIDIA shader library post effects (render-target textures by semantic, ViewportRatio,
// technique and pass Script annotations, Draw=Buffer). The scene is drawn into SceneMap,
// blurred horizontally into BlurMap, then vertically onto the screen. vs.1.1 + ps.1.1, so
// a GeForce3 runs it. Licence: same as this project.

float Script : STANDARDSGLOBAL <
    string UIWidget = "none";
    string ScriptClass = "scene";
    string ScriptOrder = "postprocess";
    string ScriptOutput = "color";
    string Script = "Technique=Blur;";
> = 0.8;

float4 ClearColor < string UIWidget = "color"; string UIName = "Background"; > = {0, 0, 0, 1};
float ClearDepth < string UIWidget = "none"; > = 1.0;
float4 ViewportSize : VIEWPORTPIXELSIZE < string UIWidget = "none"; >;

texture SceneMap : RENDERCOLORTARGET <
    float2 ViewportRatio = {1.0, 1.0};
    int MipLevels = 1;
    string Format = "A8R8G8B8";
    string UIWidget = "None";
>;
texture BlurMap : RENDERCOLORTARGET < float2 ViewportRatio = {1.0, 1.0}; string Format = "A8R8G8B8"; >;
texture DepthBuffer : RENDERDEPTHSTENCILTARGET < float2 ViewportRatio = {1.0, 1.0}; string Format = "D24S8"; >;

texture SceneTexture < string Procedural = "checker"; string UIName = "Object texture"; >;

sampler SceneSampler = sampler_state {
    Texture = <SceneMap>; MinFilter = Point; MagFilter = Point; MipFilter = None;
    AddressU = Clamp; AddressV = Clamp;
};
sampler BlurSampler = sampler_state {
    Texture = <BlurMap>; MinFilter = Point; MagFilter = Point; MipFilter = None;
    AddressU = Clamp; AddressV = Clamp;
};

// Four taps at texel offsets -1, 0, +1, +2 along one axis, at texel centres: a D3D9 pixel
// centre is at an integer position, so the quad's uv there is a texel corner; +0.5 texel.
PixelShader Average4 = asm {
    ps_1_1
    def c0, 0.25, 0.25, 0.25, 0.25
    tex t0
    tex t1
    tex t2
    tex t3
    mul r0, t0, c0
    mad r0, t1, c0, r0
    mad r0, t2, c0, r0
    mad r0, t3, c0, r0
};

technique Blur <
    string Script = "RenderColorTarget0=SceneMap;"
                    "RenderDepthStencilTarget=DepthBuffer;"
                    "ClearSetColor=ClearColor;"
                    "ClearSetDepth=ClearDepth;"
                    "Clear=Color;"
                    "Clear=Depth;"
                    "Pass=Scene;"
                    "Pass=Horizontal;"
                    "Pass=Vertical;";
> {
    pass Scene < string Script = "Draw=Geometry;"; > {
        Lighting = false;
        Texture[0] = <SceneTexture>;
        ColorOp[0] = Modulate; ColorArg1[0] = Texture; ColorArg2[0] = Diffuse;
        AlphaOp[0] = SelectArg1; AlphaArg1[0] = Diffuse;
    }
    pass Horizontal < string Script = "RenderColorTarget0=BlurMap; Draw=Buffer;"; > {
        ZEnable = false;
        Sampler[0] = <SceneSampler>; Sampler[1] = <SceneSampler>;
        Sampler[2] = <SceneSampler>; Sampler[3] = <SceneSampler>;
        VertexShaderConstant[4] = <ViewportSize>;
        VertexShader = asm {
            vs_1_1
            dcl_position  v0
            dcl_texcoord0 v7
            def c5, -0.5, 0.5, 1.5, 2.5
            mov oPos, v0
            rcp r0.x, c4.x
            rcp r0.y, c4.y
            mad r1.y, r0.y, c5.y, v7.y
            mad oT0.x, r0.x, c5.x, v7.x
            mad oT1.x, r0.x, c5.y, v7.x
            mad oT2.x, r0.x, c5.z, v7.x
            mad oT3.x, r0.x, c5.w, v7.x
            mov oT0.y, r1.y
            mov oT1.y, r1.y
            mov oT2.y, r1.y
            mov oT3.y, r1.y
        };
        PixelShader = <Average4>;
    }
    pass Vertical < string Script = "RenderColorTarget0=; Draw=Buffer;"; > {
        ZEnable = false;
        Sampler[0] = <BlurSampler>; Sampler[1] = <BlurSampler>;
        Sampler[2] = <BlurSampler>; Sampler[3] = <BlurSampler>;
        VertexShaderConstant[4] = <ViewportSize>;
        VertexShader = asm {
            vs_1_1
            dcl_position  v0
            dcl_texcoord0 v7
            def c5, -0.5, 0.5, 1.5, 2.5
            mov oPos, v0
            rcp r0.x, c4.x
            rcp r0.y, c4.y
            mad r1.x, r0.x, c5.y, v7.x
            mad oT0.y, r0.y, c5.x, v7.y
            mad oT1.y, r0.y, c5.y, v7.y
            mad oT2.y, r0.y, c5.z, v7.y
            mad oT3.y, r0.y, c5.w, v7.y
            mov oT0.x, r1.x
            mov oT1.x, r1.x
            mov oT2.x, r1.x
            mov oT3.x, r1.x
        };
        PixelShader = <Average4>;
    }
}
