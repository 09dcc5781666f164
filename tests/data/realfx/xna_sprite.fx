// Look-alike of an XNA game's effect (written for this project, not copied): HLSL only,
// parameters without semantics the game sets by name, a technique of `compile` shaders.
// World/View/Projection: the host binds them by name (the XNA convention), as the game set
// them; --set or the scene's params override.

float4x4 World;
float4x4 View;
float4x4 Projection;
float4 Tint = float4(1, 1, 1, 1);
texture SpriteTexture;
sampler SpriteSampler = sampler_state { Texture = <SpriteTexture>; MinFilter = Linear; MagFilter = Linear; };

struct VSOut { float4 Position : POSITION0; float2 Uv : TEXCOORD0; };

VSOut SpriteVS(float4 position : POSITION0, float2 uv : TEXCOORD0)
{
    VSOut o;
    o.Position = mul(mul(mul(position, World), View), Projection);
    o.Uv = uv;
    return o;
}

float4 SpritePS(float2 uv : TEXCOORD0) : COLOR0
{
    return tex2D(SpriteSampler, uv) * Tint;
}

technique Sprite
{
    pass Pass1
    {
        VertexShader = compile vs_2_0 SpriteVS();
        PixelShader = compile ps_2_0 SpritePS();
    }
}
