// brdf.fx technique tec0, lowered for geforce3
// pass 1 of 1: p0
#version 330 core
// fragment shader for IR program 7b5119137327611b
in vec4 vary_color0;
in vec4 vary_texcoord0;
in vec4 vary_texcoord1;
in vec4 vary_texcoord2;
in vec4 vary_texcoord3;
uniform sampler2D sampler0;
uniform sampler2D sampler1;
uniform sampler2D sampler2;
uniform sampler2D sampler3;
layout(location = 0, index = 0) out vec4 frag_color;

void main() {
#line 11
    vec4 v0 = vary_texcoord0;  // %0 = input texcoord0
    vec4 v1 = texture(sampler0, v0.xy);  // %1 = sample %0 sampler=0
    vec4 v2 = vary_texcoord1;  // %2 = input texcoord1
    vec4 v3 = texture(sampler1, v2.xy);  // %3 = sample %2 sampler=1
    vec4 v4 = vary_texcoord2;  // %4 = input texcoord2
    vec4 v5 = texture(sampler2, v4.xy);  // %5 = sample %4 sampler=2
    vec4 v6 = vary_texcoord3;  // %6 = input texcoord3
    vec4 v7 = texture(sampler3, v6.xy);  // %7 = sample %6 sampler=3
    vec4 v8 = (v1 * v3);  // %8 = mul %1, %3
    vec4 v9 = clamp(v8, -1.0, 1.0);  // %9 = clamp %8 lo=-1.0 hi=1.0
    vec4 v10 = (sign(clamp(v9, -1.0, 1.0)) * floor(abs(clamp(v9, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %10 = quantize %9 bits=9 signed=true
    vec4 v11 = (v10 * v5);  // %11 = mul %10, %5
    vec4 v12 = clamp(v11, -1.0, 1.0);  // %12 = clamp %11 lo=-1.0 hi=1.0
    vec4 v13 = (sign(clamp(v12, -1.0, 1.0)) * floor(abs(clamp(v12, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %13 = quantize %12 bits=9 signed=true
    vec4 v14 = (v13 * v7);  // %14 = mul %13, %7
    vec4 v15 = clamp(v14, -1.0, 1.0);  // %15 = clamp %14 lo=-1.0 hi=1.0
    vec4 v16 = (sign(clamp(v15, -1.0, 1.0)) * floor(abs(clamp(v15, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %16 = quantize %15 bits=9 signed=true
    vec4 v17 = vary_color0;  // %17 = input color0
    vec4 v18 = (v16 * v17);  // %18 = mul %16, %17
    vec4 v19 = clamp(v18, -1.0, 1.0);  // %19 = clamp %18 lo=-1.0 hi=1.0
    vec4 v20 = (sign(clamp(v19, -1.0, 1.0)) * floor(abs(clamp(v19, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %20 = quantize %19 bits=9 signed=true
    vec4 v21 = clamp(v20, 0.0, 1.0);  // %21 = saturate %20
    vec4 out_color0 = v21;  // output color0 = %21
#line 10000
    vec4 color = out_color0;
    frag_color = color;
}
