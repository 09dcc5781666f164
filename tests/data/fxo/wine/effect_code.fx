        Texture2D tex;
        float f <float a = 1.0;>;
        string s;
        float skipped : register(c4);

        float4 vs0_main(float4 pos : POSITION) : POSITION
        {
            return pos;
        }

        vertexshader vs = compile vs_2_0 vs0_main();

        technique tech0 <float a = 1.0;>
        {
            pass p
            {
                VertexShader = vs;
            }
        }

        float4 vs1_main(float4 pos : POSITION) : POSITION
        {
            return skipped;
        }

        technique tech1
        {
            pass p
            {
                VertexShader = compile vs_2_0 vs1_main();
            }
        }
