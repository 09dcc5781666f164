// Ours: a pass whose ColorWriteEnable comes from a parameter the application was to set
// (as engines' material files did); nothing sets it here, so it reads 0.
float4x4 WorldViewProj : WORLDVIEWPROJECTION;
int colorWriteEnable;
float4 Colour = float4(0.2, 0.8, 0.3, 1.0);
float4 vs_main(float4 p : POSITION) : POSITION { return mul(p, WorldViewProj); }
float4 ps_main() : COLOR0 { return Colour; }
technique Flat
{
    pass p0
    {
        ColorWriteEnable = <colorWriteEnable>;
        VertexShader = compile vs_2_0 vs_main();
        PixelShader = compile ps_2_0 ps_main();
    }
}
