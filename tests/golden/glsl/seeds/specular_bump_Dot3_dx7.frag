// specular_bump.fx technique Dot3_dx7, lowered for geforce2
// pass 1 of 1: P0
#version 330 core
// fragment shader for IR program 3245fb4c5dd03c0f
in vec4 vary_color0;
in vec4 vary_texcoord0;
in vec4 vary_texcoord1;
uniform sampler2D sampler0;
uniform sampler2D sampler1;
layout(location = 0, index = 0) out vec4 frag_color;

void main() {
#line 7
    vec4 v0 = vary_color0;  // %0 = input color0
    vec4 v1 = vary_texcoord0;  // %1 = input texcoord0
    vec4 v2 = texture(sampler0, v1.xy);  // %2 = sample %1 sampler=0
    vec4 v3 = vec4(0.5, 0.5, 0.5, 0.5);  // %3 = const (0.5, 0.5, 0.5, 0.5)
    vec4 v4 = (v2 - v3);  // %4 = sub %2, %3
    vec4 v5 = (v0 - v3);  // %5 = sub %0, %3
    vec4 v6 = vec4(dot(v4.xyz, v5.xyz));  // %6 = dp3 %4, %5
    vec4 v7 = vec4(4.0, 4.0, 4.0, 4.0);  // %7 = const (4.0, 4.0, 4.0, 4.0)
    vec4 v8 = (v6 * v7);  // %8 = mul %6, %7
    vec4 v9 = clamp(v8, 0.0, 1.0);  // %9 = saturate %8
    vec4 v10 = (sign(clamp(v9, 0.0, 1.0)) * floor(abs(clamp(v9, 0.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %10 = quantize %9 bits=8
    vec4 v11 = vary_texcoord1;  // %11 = input texcoord1
    vec4 v12 = texture(sampler1, v11.xy);  // %12 = sample %11 sampler=1
    vec4 v13 = (v12 * v10);  // %13 = mul %12, %10
    vec4 v14 = vec4(v13.x, v13.y, v13.z, v10.w);  // %14 = merge %13, %10 mask=w
    vec4 v15 = (sign(clamp(v14, 0.0, 1.0)) * floor(abs(clamp(v14, 0.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %15 = quantize %14 bits=8
    vec4 out_color0 = v15;  // output color0 = %15
#line 10000
    vec4 color = out_color0;
    frag_color = color;
}
