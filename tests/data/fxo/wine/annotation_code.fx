        float f <float a = 1.0;>;

        float4 vs_main(float4 pos : POSITION) : POSITION
        {
            return pos;
        }

        technique tech0
        {
            pass p
            {
                VertexShader = compile vs_2_0 vs_main();
            }
        }
